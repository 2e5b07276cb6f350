"""Format tags and material defaults are defined once (NativeSolver/include/lightsolver/
defaults.hpp): the module exposes them, the documentation and the written files agree, and the
workbench's exporter uses them (its fallback, for machines without the solver, is the same)."""
import json
import os
import re
import sys

import lightsolver
import numpy as np
import pytest

from conftest import SOURCE_DIR


def test_format_tags():
    assert lightsolver.SCENE_FORMAT == "lightsolver.scene/1"
    assert lightsolver.RESULTS_FORMAT == "lightsolver.results/1"
    assert lightsolver.OPTIMIZATION_FORMAT == "lightsolver.optimization/1"
    golden = SOURCE_DIR / "Tests" / "golden"
    assert json.loads((golden / "room.results.json").read_text())["format"] == \
        lightsolver.RESULTS_FORMAT
    assert json.loads((golden / "cornell.results.json").read_text())["format"] == \
        lightsolver.OPTIMIZATION_FORMAT
    scene = lightsolver.load_scene(str(SOURCE_DIR / "Examples" / "room" / "room.json"))
    assert lightsolver.solve(scene, photons=1000, seed=1)["format"] == lightsolver.RESULTS_FORMAT


def documented_defaults():
    """{type: {key: value}} from docs/scene-format.md's materials table: | `glass` | `ior` (1.52), ..."""
    text = (SOURCE_DIR / "docs" / "scene-format.md").read_text()
    table = {}
    for kind, cell in re.findall(r"^\| `(diffuse|mirror|glass|glossy)` \| ([^|]*)\|", text, re.M):
        values = re.findall(r"`(\w+)` \(([^)]*)\)", cell)
        table[kind] = {k: json.loads(v) for k, v in values}
    return table


def test_material_defaults_match_the_documentation():
    defaults = lightsolver.material_defaults()
    assert defaults == documented_defaults()
    assert defaults["glass"]["thin"] is False


QUAD = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
TRIS = [[0, 1, 2], [0, 2, 3]]
CEILING = [[x, y, 1.0] for x, y, _ in QUAD]


def built_scene(kind):
    """Floor (target) and ceiling of one material with every value at add_material's default."""
    s = lightsolver.Scene()
    s.add_material("mat", kind)
    s.add_mesh("floor", np.array(QUAD, float), np.array(TRIS), "mat")
    s.add_mesh("ceiling", np.array(CEILING, float), np.array(TRIS), "mat")
    s.add_light("lamp", "point", position=[0.5, 0.5, 0.5], flux_lm=1000.0)
    s.add_target("floor", "surface", mesh="floor")
    return s


def json_scene(material):
    """The same scene read from JSON, the material given as `material`."""
    return lightsolver.scene_from_json(json.dumps({
        "format": lightsolver.SCENE_FORMAT, "materials": {"mat": material},
        "meshes": [{"name": "floor", "material": "mat", "vertices": QUAD, "triangles": TRIS},
                   {"name": "ceiling", "material": "mat", "vertices": CEILING,
                    "triangles": TRIS}],
        "luminaires": [{"name": "lamp", "type": "point", "flux_lm": 1000.0,
                        "position": [0.5, 0.5, 0.5]}],
        "targets": [{"name": "floor", "type": "surface", "mesh": "floor"}]}))


def floor(scene):
    t = lightsolver.solve(scene, photons=20000, seed=3, backend="embree")["targets"][0]
    return t["mean_lux"], t["hits"]


@pytest.mark.parametrize("kind", ["diffuse", "mirror", "glass", "glossy"])
def test_add_material_and_the_scene_reader_share_the_defaults(kind):
    # Same photons (same seed) through the same geometry: equal numbers mean equal materials.
    assert floor(built_scene(kind)) == floor(json_scene({"type": kind}))
    written = dict(lightsolver.material_defaults()[kind], type=kind)
    assert floor(built_scene(kind)) == floor(json_scene(written))


def test_a_changed_material_value_changes_the_numbers():
    # The comparison above can fail: another reflectance gives other numbers.
    assert floor(built_scene("mirror")) != floor(json_scene({"type": "mirror",
                                                              "reflectance": 0.8}))


def test_workbench_export_uses_the_module_and_its_fallback_agrees(monkeypatch):
    # The module under test, not the newest build folder's (run.candidate_dirs: a build-no-mpi
    # beside build/ is often newer), and sys.path as it was afterwards: load_module prepends
    # the folder it chose, which later tests' subprocesses would inherit (test_mpi.py).
    monkeypatch.setenv("LIGHTSOLVER_PYTHONPATH", os.path.dirname(lightsolver.__file__))
    monkeypatch.setattr(sys, "path", list(sys.path))
    sys.path.insert(0, str(SOURCE_DIR / "Workbench"))
    try:
        from lighting.export import defaults
        from lighting.solver import run
    finally:
        sys.path.pop(0)
    assert run.load_module() is lightsolver
    assert defaults.scene_format() == lightsolver.SCENE_FORMAT
    assert defaults.material_defaults() == lightsolver.material_defaults()
    assert defaults.FALLBACK_SCENE_FORMAT == lightsolver.SCENE_FORMAT
    assert defaults.FALLBACK_MATERIAL_DEFAULTS == lightsolver.material_defaults()
