# SPDX-License-Identifier: LGPL-2.1-or-later
"""Example: build a small office (Arch walls, window, desk, ceiling luminaires), analyse it,
print the results table and save the .FCStd.

Run it headless (after scripts/install-workbench.sh, or from the source tree):

    freecadcmd Examples/office.py
    LIGHTING_OUT=/tmp/office.FCStd LIGHTING_PHOTONS=500000 freecadcmd Examples/office.py

or in the GUI, also right after FreeCAD starts on its Start page: ``freecad
Examples/office.py``, Macro > Macros... > Execute, or in the Python console
``exec(open("/path/to/Examples/office.py").read())``. In the GUI it ends on the Lighting
workbench with the 3D view fitted and the ceiling shown transparent.

Environment: LIGHTING_OUT (the .FCStd to write; default <tmp>/lighting-example/office.FCStd),
LIGHTING_PHOTONS (default 200000), LIGHTING_SEED (default 1), LIGHTING_BUILD_ONLY=1 (build
and save without solving). The scene and results JSON go to '<file>_lighting/' next to it;
re-run them with ``lightsolver run <that folder>/LightingAnalysis/scene.json``.
Headless, the exit status is 0 on success and 1 with a clear message on failure.
"""
import os
import sys
import tempfile
import traceback


def _examples_dir() -> str:
    """This file's folder. ``exec(open(...).read())`` in the Python console has no
    ``__file__`` of its own (or another macro's): then the checkout of the installed
    workbench (a symlink to its Workbench/ folder), then ./Examples."""
    candidates = []
    if globals().get("__file__"):
        candidates.append(os.path.dirname(os.path.abspath(globals()["__file__"])))
    try:
        import lighting

        checkout = os.path.dirname(os.path.dirname(os.path.dirname(
            os.path.realpath(lighting.__file__))))
        candidates.append(os.path.join(checkout, "Examples"))
    except ImportError:  # not installed: only the source checkout can provide it
        pass
    candidates.append(os.path.abspath("Examples"))
    for folder in candidates:
        if os.path.exists(os.path.join(folder, "office_model.py")):
            return folder
    return candidates[0]


def _setup_paths() -> None:
    """Make ``lighting`` and ``office_model`` importable from a source checkout too."""
    here = _examples_dir()
    for path in (here, os.path.join(os.path.dirname(here), "Workbench")):
        if os.path.isdir(path) and path not in sys.path:
            sys.path.insert(0, path)


def main() -> int:
    """Build, analyse, print, save; returns the exit status."""
    _setup_paths()
    import lighting
    import office_model

    out = os.environ.get("LIGHTING_OUT") or os.path.join(
        tempfile.gettempdir(), "lighting-example", "office.FCStd")
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    photons = int(os.environ.get("LIGHTING_PHOTONS", "200000"))
    seed = int(os.environ.get("LIGHTING_SEED", "1"))
    doc = office_model.build_office(photons=photons, seed=seed)
    office_model.show_in_gui(doc)  # GUI only: workbench, fitted view, transparent ceiling
    # Save first, so the scene lands next to the file ('office_lighting/').
    doc.saveAs(out)
    if os.environ.get("LIGHTING_BUILD_ONLY") == "1":
        print(f"office: model saved to {out} (not analysed)")
        return 0
    try:
        result = lighting.analyze(doc)
    except lighting.LightingError as exc:
        print(f"office: analysis failed:\n{exc}")
        doc.save()
        return 1
    print(result.table())
    print(f"office: scene {result.scene_file}")
    print(f"office: results {result.results_file}")
    doc.save()
    print(f"office: saved {out}")
    office_model.show_in_gui(doc)  # again: the results' colours are painted now
    return 0


try:
    _status = main()
except Exception:  # noqa: BLE001 - print the reason; freecadcmd would hide it
    traceback.print_exc()
    _status = 1
import FreeCAD as _FreeCAD  # noqa: E402

if not _FreeCAD.GuiUp:  # headless: report the status (freecadcmd exits 0 otherwise)
    sys.exit(_status)
