"""Scene.add_light / add_target: one call for every luminaire and target type, read by the
scene file's own reader (the type tables of NativeSolver/src/core), so a scene built in Python
and the same scene read from JSON are the same scene."""
import json

import numpy as np
import pytest

import lightsolver
from conftest import SOURCE_DIR

IES = str(SOURCE_DIR / "Resources/luminaires/downlight.ies")

# One entry of every luminaire type, as a scene file spells it (name and type first).
LIGHTS = [
    {"name": "bulb", "type": "point", "position": [1.0, 1.0, 2.5], "flux_lm": 800.0},
    {"name": "spot", "type": "spot", "position": [2.0, 1.0, 2.5], "direction": [0, 0, -1],
     "beam_angle_deg": 30.0, "field_angle_deg": 60.0, "flux_lm": 600.0},
    {"name": "panel", "type": "area", "corner": [0.5, 2.0, 2.9], "edge1": [0, 0.6, 0],
     "edge2": [0.6, 0, 0], "flux_lm": 3000.0},
    {"name": "sun", "type": "directional", "direction": [0.3, 0.2, -1.0],
     "corner": [0.0, 0.0, 3.5], "edge1": [1.0, 0, 0], "edge2": [0, 1.0, 0],
     "illuminance_lx": 2000.0},
    {"name": "dl", "type": "photometric", "file": IES, "position": [3.0, 2.0, 2.8],
     "aim": [0, 0, -1], "rotation_deg": 15.0, "flux_lm": 1200.0},
]
FLOOR = {"vertices": [[0, 0, 0], [4, 0, 0], [4, 3, 0], [0, 3, 0]],
         "triangles": [[0, 1, 2], [0, 2, 3]]}
TARGETS = [
    {"name": "floor", "type": "surface", "mesh": "floor"},
    {"name": "desk", "type": "grid", "corner": [0.5, 0.5, 0.8], "edge1": [3.0, 0, 0],
     "edge2": [0, 2.0, 0], "cells": [6, 4]},
]


def scene_json() -> str:
    return json.dumps({"format": lightsolver.SCENE_FORMAT,
                       "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
                       "meshes": [dict(FLOOR, name="floor", material="grey")],
                       "luminaires": LIGHTS, "targets": TARGETS,
                       "settings": {"photons": 200_000, "seed": 7}})


def built_in_python() -> "lightsolver.Scene":
    s = lightsolver.Scene()
    s.add_material("grey", reflectance=0.5)
    s.add_mesh("floor", np.array(FLOOR["vertices"], float), np.array(FLOOR["triangles"]), "grey")
    for entry in LIGHTS:
        fields = {k: v for k, v in entry.items() if k not in ("name", "type")}
        s.add_light(entry["name"], entry["type"], **fields)
    for entry in TARGETS:
        fields = {k: v for k, v in entry.items() if k not in ("name", "type")}
        s.add_target(entry["name"], entry["type"], **fields)
    return s


def test_every_type_gives_the_scene_files_results(tmp_path):
    path = tmp_path / "scene.json"
    path.write_text(scene_json())
    from_file = lightsolver.solve(lightsolver.load_scene(str(path)), photons=200_000, seed=7)
    from_python = lightsolver.solve(built_in_python(), photons=200_000, seed=7)
    for a, b in zip(from_file["targets"], from_python["targets"]):
        assert a["name"] == b["name"]
        assert a["mean_lux"] == b["mean_lux"] and a["mean_lux"] > 0
    assert np.array_equal(from_file["targets"][1]["cells_lux"],
                          from_python["targets"][1]["cells_lux"])


def test_numpy_values_are_accepted():
    s = lightsolver.Scene()
    s.add_light("lamp", "point", position=np.array([0.0, 0.0, 2.0]), flux_lm=np.float32(100))
    s.add_target("g", "grid", corner=np.zeros(3), edge1=np.array([1.0, 0, 0]),
                 edge2=np.array([0, 1.0, 0]), cells=np.array([2, 2]))
    assert lightsolver.solve(s, photons=10_000)["targets"][0]["mean_lux"] > 0


@pytest.mark.parametrize("call, message", [
    (lambda s: s.add_light("a", "point", position=[0, 0, 1]),
     r'add_light\("a"\).*missing required key "flux_lm"'),
    (lambda s: s.add_light("b", "point", position=[0, 0, 1], flux_lm=1, colour="red"),
     r'add_light\("b"\).*colour'),
    (lambda s: s.add_light("c", "laser", position=[0, 0, 1]),
     r'add_light\("c"\).*unknown luminaire type "laser".*point, spot, area'),
    (lambda s: s.add_light("d", "point", position=[0, float("nan"), 1], flux_lm=1),
     r'add_light\("d"\): position\[1\]'),
    (lambda s: s.add_light("e", "spot", position=[0, 0, 1], direction="down",
                           beam_angle_deg=10, field_angle_deg=20, flux_lm=1),
     r'add_light\("e"\): direction'),
    (lambda s: s.add_target("f", "surface", mesh="nowhere"),
     r'add_target\("f"\): mesh.*unknown mesh "nowhere"'),
    (lambda s: s.add_target("g", "grid", corner=[0, 0, 0], edge1=[1, 0, 0], edge2=[0, 1, 0],
                            cells=[0, 3]),
     r'add_target\("g"\): cells.*at least 1x1'),
])
def test_bad_fields_name_the_call_and_the_key(call, message):
    s = lightsolver.Scene()
    with pytest.raises(lightsolver.InputError, match=message):
        call(s)


def test_an_unconvertible_value_is_a_type_error():
    s = lightsolver.Scene()
    with pytest.raises(TypeError, match=r'add_light\("x"\)'):
        s.add_light("x", "point", position=[0, 0, 1], flux_lm=object())
