#!/usr/bin/python3
"""Run one suite of the Lighting workbench tests inside ``freecadcmd`` with the real status.

    /usr/bin/python3 Tests/workbench/run_tests.py SUITE [unittest args...]

SUITE is a module ``test_<SUITE>.py`` of this folder (objects, export, check, solver,
persistence, example, optimize, files, app_imports). ``freecadcmd script.py`` always exits 0,
so the suite runs through ``freecadcmd -c`` and ``sys.exit`` (see fc_runner.py). The workbench is
installed into a throw-away FreeCAD user folder (FREECAD_USER_HOME, ``Mod/Lighting``
symlink) — the layout scripts/install-workbench.sh creates — so the user's own FreeCAD
settings are untouched.

Exit status: 0 passed, 1 failed, 77 every test skipped (ctest SKIP_RETURN_CODE).
Environment: LIGHTSOLVER_PYTHONPATH (solver module folder), LIGHTSOLVER_CLI (CLI program),
LIGHTSOLVER_REQUIRED=1 (a missing solver fails instead of skipping; CMake sets it when it
builds the module), FREECADCMD (default freecadcmd)."""
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def make_user_home(root: str) -> str:
    """A FreeCAD user folder with the workbench installed as a symlink."""
    home = os.path.join(root, "freecad-user")
    os.makedirs(os.path.join(home, "Mod"), exist_ok=True)
    link = os.path.join(home, "Mod", "Lighting")
    if not os.path.lexists(link):
        os.symlink(os.path.join(REPO, "Workbench"), link)
    return home


def freecad_env(root: str) -> dict:
    """Environment for freecadcmd/freecad runs of the tests."""
    env = dict(os.environ)
    home = make_user_home(root)
    env["FREECAD_USER_HOME"] = home
    env["LIGHTING_TEST_TMP"] = root
    env["LIGHTING_SOURCE_DIR"] = REPO
    return env


def main(argv: list) -> int:
    if len(argv) < 2:
        print(__doc__)
        return 2
    suite = argv[1]
    if not os.path.exists(os.path.join(HERE, f"test_{suite}.py")):
        print(f"run_tests: no suite {suite!r} (test_{suite}.py)")
        return 2
    freecadcmd = os.environ.get("FREECADCMD", "freecadcmd")
    if shutil.which(freecadcmd) is None:
        print(f"run_tests: {freecadcmd} not found: install FreeCAD (apt-get install freecad)")
        return 77
    root = tempfile.mkdtemp(prefix=f"lighting-{suite}-")
    env = freecad_env(root)
    code = ("import sys; sys.path.insert(0, %r); import fc_runner; "
            "sys.exit(fc_runner.main(%r, %r))" % (HERE, suite, argv[2:]))
    print(f"run_tests: suite {suite}, work folder {root}", flush=True)
    proc = subprocess.run([freecadcmd, "-c", code], env=env, cwd=root)
    status = proc.returncode
    if status == 0 and os.environ.get("LIGHTING_KEEP_TMP") != "1":
        shutil.rmtree(root, ignore_errors=True)
    print(f"run_tests: suite {suite} exit status {status}", flush=True)
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
