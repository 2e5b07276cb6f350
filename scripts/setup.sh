#!/usr/bin/env bash
# Fresh Debian 12 -> everything installed and built: packages, solver, Python module, and the
# FreeCAD workbench (when its installer is present).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
if [ -f scripts/install-workbench.sh ]; then bash scripts/install-workbench.sh; fi
