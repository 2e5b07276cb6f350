#!/usr/bin/python3
"""Run one GUI scenario in a real FreeCAD under Xvfb and report its status.

    /usr/bin/python3 Tests/workbench/gui/run_scenario.py NAME [--update-docs]

NAME is ``scenario_<NAME>.py`` of this folder. FreeCAD starts as a user's first start does:
a fresh user folder with only the Lighting workbench installed, its default window size, the
Start page. The scenario writes status.json (guilib.finish); the run passes when it says
``passed`` with no errors. --update-docs copies the screenshots the scenario marked for the
docs into docs/. Exit status: 0 passed, 1 failed, 77 skipped (no xvfb-run/freecad)."""
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from run_tests import REPO, freecad_env  # noqa: E402


def main(argv: list) -> int:
    if len(argv) < 2:
        print(__doc__)
        return 2
    name = argv[1]
    macro = os.path.join(HERE, f"scenario_{name}.py")
    if not os.path.exists(macro):
        print(f"run_scenario: no scenario {name!r} ({macro})")
        return 2
    for tool in ("xvfb-run", "freecad"):
        if shutil.which(tool) is None:
            print(f"run_scenario: {tool} not found; skipped")
            return 77
    root = tempfile.mkdtemp(prefix=f"lighting-gui-{name}-")
    env = freecad_env(root)
    out = os.path.join(root, "out")
    os.makedirs(out)
    env.update(LIGHTING_GUI_OUT=out, QTWEBENGINE_DISABLE_SANDBOX="1", LIGHTING_GUI_SCENARIO=name,
               PYTHONPATH=os.pathsep.join(filter(None, [HERE, env.get("PYTHONPATH")])))
    cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "freecad", macro]
    print("run_scenario:", " ".join(cmd), flush=True)
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=560, cwd=root)
    status_file = os.path.join(out, "status.json")
    if not os.path.exists(status_file):
        print(proc.stdout[-4000:], proc.stderr[-4000:])
        print(f"run_scenario: {name}: FreeCAD ended without status.json: FAILED")
        return 1
    with open(status_file, encoding="utf-8") as stream:
        status = json.load(stream)
    print(json.dumps({k: v for k, v in status.items() if k != "log"}, indent=1))
    for image, path in status.get("images", {}).items():
        print(f"screenshot ({image}): {path}")
    if "--update-docs" in argv and status.get("passed"):
        for image, docs_name in status.get("docs_images", {}).items():
            target = os.path.join(REPO, "docs", "images", docs_name)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copyfile(status["images"][image], target)
            print(f"run_scenario: copied {image} to {target}")
    for problem in status.get("errors", []):
        print(f"run_scenario: {name}: FAILED: {problem}")
    ok = bool(status.get("passed")) and not status.get("errors")
    if not ok:
        print("\n".join(status.get("log", [])[-40:]))
    print(f"run_scenario: {name}:", "passed" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
