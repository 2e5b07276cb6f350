"""The one scene check (lightsolver.check_scene*) and photometric facts from the native parsers
(lightsolver.photometry_summary): what the workbench's Check stage and luminaire objects use."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

import lightsolver


def floor_scene(flux_lm: float = 1000.0) -> "lightsolver.Scene":
    """A 2 m x 2 m floor, a lamp 1 m above it, the floor as the target."""
    s = lightsolver.Scene()
    s.add_material("grey", reflectance=0.5)
    v = np.array([[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0]], dtype=float)
    s.add_mesh("floor", v, np.array([[0, 1, 2], [0, 2, 3]]), "grey")
    s.add_light("lamp", "point", position=[1, 1, 1], flux_lm=flux_lm)
    s.add_target("floor", "surface", mesh="floor")
    return s


def fields(issues):
    return [i["field"] for i in issues]


def test_valid_scene_has_no_errors(room_scene: Path):
    check = lightsolver.check_scene_file(str(room_scene))
    assert check["errors"] == []
    assert all(set(w) == {"field", "file", "line", "message"} for w in check["warnings"])


def test_error_names_field_and_file(room_scene: Path):
    doc = json.loads(room_scene.read_text())
    doc["luminaires"][1]["flux_lm"] = -5.0
    check = lightsolver.check_scene_json(json.dumps(doc), str(room_scene.parent))
    assert len(check["errors"]) == 1  # one bad value, one error
    error = check["errors"][0]
    assert error["field"] == "luminaires[1].flux_lm"
    assert error["file"] == "<string>" and error["line"] == 0
    assert "-5" in error["message"] and "luminaires[1]" not in error["message"]


def test_every_bad_entry_is_listed_in_file_order(room_scene: Path):
    """The check goes on after an error: each bad entry's first error, in file order, so a
    user fixes them all in one round instead of one per Check."""
    doc = json.loads(room_scene.read_text())
    doc["luminaires"][1]["flux_lm"] = -5.0
    doc["luminaires"][0]["flux_lm"] = 2e13
    doc["settings"]["confidence"] = 1.5
    doc["targets"].append({"name": "tiny", "type": "grid", "corner": [0, 0, 0],
                           "edge1": [1e-9, 0, 0], "edge2": [0, 1, 0], "cells": [1, 1]})
    check = lightsolver.check_scene_json(json.dumps(doc), str(room_scene.parent))
    last = len(doc["targets"]) - 1
    assert fields(check["errors"]) == ["luminaires[0].flux_lm", "luminaires[1].flux_lm",
                                       f"targets[{last}].edge1", "settings.confidence"]
    assert check["warnings"] == []  # warnings need a valid scene
    # The same scene through validate() (a run) still stops at the first of them.
    with pytest.raises(lightsolver.InputError, match=r"luminaires\[0\]\.flux_lm"):
        lightsolver.scene_from_json(json.dumps(doc), str(room_scene.parent))


def test_a_target_on_a_bad_mesh_is_not_reported_twice():
    s = floor_scene()
    s.add_mesh("broken", np.array([[0, 0, 1], [1, np.nan, 1], [0, 1, 1]]),
               np.array([[0, 1, 2]]), "grey")
    s.add_target("on broken", "surface", mesh="broken")
    s.add_light("bad", "point", position=[1, 1, 1], flux_lm=-1.0)
    check = lightsolver.check_scene(s)
    assert fields(check["errors"]) == ["meshes[1].vertices[1]", "luminaires[1].flux_lm"]


def test_unreadable_file_is_one_error(tmp_path: Path):
    check = lightsolver.check_scene_file(str(tmp_path / "missing.json"))
    assert len(check["errors"]) == 1 and check["errors"][0]["file"].endswith("missing.json")
    (tmp_path / "bad.json").write_text("{ not json")
    check = lightsolver.check_scene_file(str(tmp_path / "bad.json"))
    assert len(check["errors"]) == 1 and check["warnings"] == []


def test_flux_zero_is_a_switched_off_luminaire():
    """One rule (docs/scene-format.md): 0 lm is accepted; only a scene emitting nothing warns."""
    s = floor_scene()
    s.add_light("off", "point", position=[0.5, 0.5, 1], flux_lm=0.0)
    check = lightsolver.check_scene(s)
    assert check["errors"] == [] and check["warnings"] == []
    check = lightsolver.check_scene(floor_scene(0.0))
    assert check["errors"] == []
    assert fields(check["warnings"]) == ["luminaires"]
    assert "zero flux" in check["warnings"][0]["message"]


def test_check_scene_leaves_the_scene_unchanged():
    """validate() drops degenerate triangles; the check works on a copy and reports the drop."""
    s = floor_scene()
    v = np.array([[0, 0, 2], [1, 0, 2], [2, 0, 2]], dtype=float)  # collinear: zero area
    s.add_mesh("sliver", v, np.array([[0, 1, 2]]), "grey")
    check = lightsolver.check_scene(s)
    assert check["errors"] == []
    assert fields(check["warnings"]) == ["meshes[1]"]
    assert "dropped" in check["warnings"][0]["message"]
    assert s.triangle_count == 3


def test_missing_target_is_an_error():
    s = lightsolver.Scene()
    s.add_material("grey", reflectance=0.5)
    s.add_light("lamp", "point", position=[1, 1, 1], flux_lm=100.0)
    check = lightsolver.check_scene(s)
    assert fields(check["errors"]) == ["targets"]


def test_coincident_targets_are_warned_with_their_mesh():
    """Two targets in one plane facing the same way (a rug target on the floor target): the
    share each gets is arbitrary; prepare() finds it and the check says so."""
    s = floor_scene()
    v = np.array([[0.5, 0.5, 0], [1.5, 0.5, 0], [1.5, 1.5, 0], [0.5, 1.5, 0]], dtype=float)
    s.add_mesh("rug", v, np.array([[0, 1, 2], [0, 2, 3]]), "grey")
    s.add_target("rug", "surface", mesh="rug")
    check = lightsolver.check_scene(s)
    assert check["errors"] == []
    assert fields(check["warnings"]) == ["meshes[0]"]
    assert "rug" in check["warnings"][0]["message"]
    assert "arbitrary" in check["warnings"][0]["message"]


IES_STEP = """IESNA:LM-63-2002
[TEST] step
TILT=NONE
2 500 1 5 1 1 2 0 0 0
1 1 10
0 30 60 90 180
0
100 100 100 0 0
"""

IES_ISOTROPIC_ABSOLUTE = """IESNA:LM-63-2002
[TEST] isotropic
TILT=NONE
1 -1 1 3 1 1 2 0 0 0
1 1 10
0 90 180
0
100 100 100
"""


def test_photometry_summary_step(tmp_path: Path):
    """100 cd to gamma 60, linear to 0 at 90: 50 % at 75 deg, 10 % at 87 deg (full angles 150
    and 174 in both planes of a rotational file); lamp lumens 2 x 500."""
    path = tmp_path / "step.ies"
    path.write_text(IES_STEP)
    s = lightsolver.photometry_summary(str(path))
    assert s["format"] == "ies" and s["symmetry"] == "rotational"
    assert s["lamp_lumens_lm"] == 1000.0 and not s["absolute_photometry"]
    assert s["peak_cd"] == 100.0 and s["peak_vertical_deg"] == 0.0
    for beam, field in zip(s["beam_angle_deg"], s["field_angle_deg"]):
        assert beam == pytest.approx(150.0, abs=0.05)
        assert field == pytest.approx(174.0, abs=0.05)
    assert "Beam angle" in s["text"]


def test_photometry_summary_absolute_isotropic(tmp_path: Path):
    """Constant 100 cd over the sphere: 400 pi lm; absolute, so no lamp lumens; the intensity
    never falls, so beam and field angles are undefined (None)."""
    path = tmp_path / "iso.ies"
    path.write_text(IES_ISOTROPIC_ABSOLUTE)
    s = lightsolver.photometry_summary(str(path))
    assert s["absolute_photometry"] and s["lamp_lumens_lm"] is None
    assert s["integrated_lumens_lm"] == pytest.approx(400.0 * math.pi, rel=1e-9)
    assert s["beam_angle_deg"] == (None, None) and s["field_angle_deg"] == (None, None)


def test_photometry_errors_name_the_file_and_line(tmp_path: Path):
    path = tmp_path / "broken.ies"
    path.write_text(IES_STEP.replace("0 30 60 90 180", "0 30 sixty 90 180"))
    with pytest.raises(lightsolver.InputError, match="broken.ies"):
        lightsolver.photometry_summary(str(path))
    scene = {"format": lightsolver.SCENE_FORMAT,
             "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
             "meshes": [{"name": "floor", "material": "grey",
                         "vertices": [[0, 0, 0], [2, 0, 0], [2, 2, 0]], "triangles": [[0, 1, 2]]}],
             "luminaires": [{"name": "l", "type": "photometric", "file": "broken.ies",
                             "position": [1, 1, 1]}],
             "targets": [{"name": "floor", "type": "surface", "mesh": "floor"}]}
    (tmp_path / "scene.json").write_text(json.dumps(scene))
    check = lightsolver.check_scene_file(str(tmp_path / "scene.json"))
    assert len(check["errors"]) == 1
    error = check["errors"][0]
    assert error["file"].endswith("broken.ies") and error["line"] > 0 and error["field"] == ""


def test_loaded_scene_is_not_warned_twice(room_scene: Path):
    """A Scene from load_scene was validated once; checking it again repeats no remark."""
    doc = json.loads(room_scene.read_text())
    doc["settings"]["confidence"] = 0.3
    scene = lightsolver.scene_from_json(json.dumps(doc), str(room_scene.parent))
    check = lightsolver.check_scene(scene)
    assert check["errors"] == []
    assert fields(check["warnings"]).count("settings.confidence") == 1


def panel_over_black_floor(with_work_plane: bool) -> "lightsolver.Scene":
    """Issue 23's case: a black floor, a 3400 lm panel facing down at 3 m, an observer grid
    with one eye at (5.5, 2, 1.2) looking +x, then (optionally) a 4 x 3 work plane at 0.8 m."""
    s = lightsolver.Scene()
    s.add_material("black", reflectance=0.0)
    v = np.array([[0, 0, 0], [8, 0, 0], [8, 4, 0], [0, 4, 0]], dtype=float)
    s.add_mesh("floor", v, np.array([[0, 1, 2], [0, 2, 3]]), "black")
    s.add_light("panel", "area", corner=[3.5, 1.5, 3.0], edge1=[0, 1, 0], edge2=[1, 0, 0],
                flux_lm=3400)
    s.add_target("eyes", "observer_grid", positions=[[5.5, 2, 1.2]], view_directions=[[1, 0, 0]])
    if with_work_plane:
        s.add_target("work plane", "grid", corner=[1, 0.5, 0.8], edge1=[6, 0, 0],
                     edge2=[0, 3, 0], cells=[4, 3])
    return s


def test_a_lit_work_plane_after_an_observer_grid_is_not_called_dark():
    """The reach check reads each target's own grid rows (its PreparedTarget): the warning names
    the eyes, which count reflected light only, and not the lit work plane."""
    s = panel_over_black_floor(True)
    check = lightsolver.check_scene(s)
    assert check["errors"] == []
    dark = [w for w in check["warnings"] if w["field"].startswith("targets")]
    assert fields(dark) == ["targets[0]"]
    assert "reflected light only" in dark[0]["message"]
    r = lightsolver.solve(s, photons=20000, seed=1)
    plane = next(t for t in r["targets"] if t["name"] == "work plane")
    assert plane["mean_lux"] > 0.0
    assert not [w for w in r["warnings"] if "work plane" in w]


def test_an_observer_grid_alone_is_checked_by_its_eyes():
    check = lightsolver.check_scene(panel_over_black_floor(False))
    assert check["errors"] == []
    assert fields([w for w in check["warnings"] if w["field"].startswith("targets")]) == [
        "targets[0]"]
