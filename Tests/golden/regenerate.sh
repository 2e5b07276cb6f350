#!/usr/bin/env bash
# Regenerates golden results from the commands in commands.json. Run it only when a change is
# meant to move the numbers, in a commit of its own that says which numbers moved, by how much
# and why (Tests/golden/README.md). LIGHTSOLVER_CLI picks the executable (default: the build
# folder's).
#
#   Tests/golden/regenerate.sh                 every golden (all backends)
#   Tests/golden/regenerate.sh room lamps      these names (a per-backend name: every backend)
#   Tests/golden/regenerate.sh lamps.vulkan    one backend's golden of one name
#   Tests/golden/regenerate.sh --backend embree   every per-backend golden of one backend
#
# Vulkan goldens are lavapipe's (commands.json sets VK_ICD_FILENAMES): regenerate them on
# lavapipe only. A per-backend name's goldens come in manifest order, so lamps_rescaled (which
# rescales lamps.<backend>.results.json) follows lamps.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cli="${LIGHTSOLVER_CLI:-$root/build/NativeSolver/cli/lightsolver}"
cd "$root"
/usr/bin/python3 - "$cli" "$@" <<'PY'
import json
import os
import subprocess
import sys

cli, *wanted = sys.argv[1:]
only_backend = None
if wanted[:1] == ["--backend"]:
    only_backend, wanted = wanted[1], wanted[2:]
manifest = json.load(open("Tests/golden/commands.json"))
per_backend = manifest["per_backend"]
unknown = [w for w in wanted if w.split(".")[0] not in manifest["commands"]
           and w.split(".")[0] not in per_backend["commands"]]
if unknown:
    sys.exit(f"unknown golden(s): {', '.join(unknown)}")


def chosen(name, backend=None):
    if only_backend is not None and backend != only_backend:
        return False
    if not wanted:
        return True
    return name in wanted or (backend is not None and f"{name}.{backend}" in wanted)


def run(args, out, env=None):
    subprocess.run([cli, *args, "--out", out], check=True, stdout=subprocess.DEVNULL,
                   env={**os.environ, **(env or {})})
    print("wrote", out)


for name, args in manifest["commands"].items():
    if chosen(name):
        run(args, f"Tests/golden/{name}.results.json")
for backend, spec in per_backend["backends"].items():
    for name, args in per_backend["commands"].items():
        if chosen(name, backend):
            run([a.replace("{backend}", backend) for a in args],
                f"Tests/golden/{name}.{backend}.results.json", spec["env"])
PY
