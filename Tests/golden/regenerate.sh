#!/usr/bin/env bash
# Regenerates the golden results from the commands in commands.json. Run it only when a change
# is meant to move the numbers, in a commit of its own that says which numbers moved and why
# (Tests/golden/README.md). LIGHTSOLVER_CLI picks the executable (default: the build folder's).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cli="${LIGHTSOLVER_CLI:-$root/build/NativeSolver/cli/lightsolver}"
cd "$root"
/usr/bin/python3 - "$cli" <<'PY'
import json
import subprocess
import sys

manifest = json.load(open("Tests/golden/commands.json"))
for name, args in manifest["commands"].items():
    out = f"Tests/golden/{name}.results.json"
    subprocess.run([sys.argv[1], *args, "--out", out], check=True, stdout=subprocess.DEVNULL)
    print("wrote", out)
PY
