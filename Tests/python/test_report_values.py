"""The report's derived values (issue 24's remaining gaps): initial values where luminaires
have different maintenance factors (the run rescaled per group by 1/MF, or said why not), the
floor area LENI is per (stated, else measured inside the walls on the plan, else a grid's,
each said), and power from the photometric file scaled with the luminaire's flux.

Fixtures: Tests/python/fixtures/report (make_fixtures.py)."""
import json

import lightsolver
import numpy as np
import pytest

from lightsolver_report import build, render_html
from lightsolver_report.floorarea import room_floor_area
from lightsolver_report.meshes import Mesh
from lightsolver_report.section import Level

from test_report import DATE, fixture

BACK_ROW = ("LuminaireLayout_r2c1", "LuminaireLayout_r2c2", "LuminaireLayout_r2c3")


def _workbench(mfs=None, flux_lm=None):
    """The workbench office's scene (a dict) with some luminaires' MF or flux changed."""
    scene, results = fixture("workbench")
    data = json.loads(scene.read_text())
    for name, mf in (mfs or {}).items():
        data["metadata"]["luminaires"][name]["maintenance_factor"] = mf
    if flux_lm is not None:
        for lum in data["luminaires"]:
            lum["flux_lm"] = flux_lm
    return scene, data, results


def _target(results, name):
    return next(t for t in results["targets"] if t["name"] == name)


def _em(target):
    """(Ēm, low, high) of a results target."""
    return target["mean_lux"], target["ci_low_lux"], target["ci_high_lux"]


# --- initial values ----------------------------------------------------------------------------

def test_a_common_mf_divides_values_and_intervals():
    scene, results = fixture("workbench")
    report = build(scene, results, date=DATE)
    assert report.common_mf == 0.8 and report.initial.available
    work = next(a for a in report.areas if a.name == "Workplane")
    init = report.initial.stats["Workplane"]
    for key, stat in (("em", work.em), ("emin", work.emin), ("emax", work.emax)):
        assert init[key].value == pytest.approx(stat.value / 0.8, rel=1e-12)
        assert init[key].low == pytest.approx(stat.low / 0.8, rel=1e-12)
        assert init[key].high == pytest.approx(stat.high / 0.8, rel=1e-12)
    assert "DeskObserver" not in report.initial.stats  # UGR has no initial value here


def test_different_mfs_per_group_give_the_run_rescaled_by_each_groups_inverse_mf():
    scene, data, results = _workbench({name: 0.7 for name in BACK_ROW})
    report = build(data, results, scene_path=scene, date=DATE)
    assert report.common_mf is None and report.initial.available
    assert report.initial.group_mfs == {"Window row": 0.8, "Back row": 0.7}
    expected = lightsolver.rescale(results, {"Window row": 1 / 0.8, "Back row": 1 / 0.7})
    for name in ("Workplane", "DeskTop_target", "NorthWall"):
        init, want, maintained = (report.initial.stats[name], _target(expected, name),
                                  _target(results, name))
        assert (init["em"].value, init["em"].low, init["em"].high) == pytest.approx(
            _em(want), rel=1e-12)
        assert init["em"].low <= init["em"].value <= init["em"].high
        # Between the maintained value ÷ the larger and ÷ the smaller MF, strictly: both
        # groups light every area.
        em = _em(maintained)[0]
        assert em / 0.8 < init["em"].value < em / 0.7
        # E_initial = Σ_g E_g / MF_g from the groups' own parts.
        parts = maintained["contributions"]
        assert init["em"].value == pytest.approx(
            parts["Window row"]["illuminance_lux"] / 0.8
            + parts["Back row"]["illuminance_lux"] / 0.7, rel=1e-9)
    grid = _target(expected, "Workplane")
    init = report.initial.stats["Workplane"]
    assert init["emin"].value == pytest.approx(grid["min_lux"], rel=1e-12)
    assert init["emax"].value == pytest.approx(grid["max_lux"], rel=1e-12)
    assert init["emin"].low <= init["emin"].value <= init["emin"].high
    html = render_html(data, results, scene_path=scene, date=DATE)
    assert "÷ MF per group" in html
    assert "maintenance factors 0.70 … 0.80 by luminaire group" in html
    assert "Initial values are not given" not in html


def test_a_group_mixing_mfs_gets_no_initial_values_and_the_page_says_why():
    scene, data, results = _workbench({"LuminaireLayout_r1c1": 0.7})
    report = build(data, results, scene_path=scene, date=DATE)
    assert not report.initial.available and report.common_mf is None
    assert "switched together in Window row" in report.initial.missing
    html = render_html(data, results, scene_path=scene, date=DATE)
    assert "Initial values are not given: luminaires with different maintenance factors" in html
    assert "Initial<br>" not in html


def test_different_mfs_without_each_groups_part_say_why():
    scene, data, results = _workbench({name: 0.7 for name in BACK_ROW})
    for target in results["targets"]:
        target.pop("contributions", None)
    report = build(data, results, scene_path=scene, date=DATE)
    assert not report.initial.available
    assert "did not keep each group's share" in report.initial.missing
    assert "Initial values are not given" in render_html(data, results, scene_path=scene,
                                                         date=DATE)


# --- LENI's floor area ---------------------------------------------------------------------------

def _room_with_energy(area_m2=None, keep=None):
    scene, results = fixture("room")
    data = json.loads(scene.read_text())
    energy = {"daylight_hours": 2000, "night_hours": 500}
    if area_m2 is not None:
        energy["area_m2"] = area_m2
    data.setdefault("metadata", {})["report"] = {"energy": energy}
    if keep is not None:
        data["meshes"] = [m for m in data["meshes"] if m["name"] in keep]
    return build(data, results, scene_path=scene, date=DATE)


def test_leni_is_per_the_stated_floor_area():
    report = _room_with_energy(area_m2=30.0)
    assert report.leni.area_m2 == 30.0 and report.leni.area_label == "floor area as stated"


def test_leni_without_a_stated_area_is_per_the_floor_inside_the_walls():
    report = _room_with_energy()
    # Examples/room: 6 m × 4 m inside its walls (single faces on round coordinates).
    assert report.leni.area_m2 == pytest.approx(24.0, abs=1e-3)
    assert "inside the walls" in report.leni.area_label
    assert report.leni.leni_kwh_m2 == pytest.approx(
        4 * 29.0 * (2000 + 500) / 1000 / report.leni.area_m2, rel=1e-12)


def test_leni_without_walls_is_per_the_largest_grid_and_says_so():
    report = _room_with_energy(keep={"floor", "desk body", "desk top"})
    grid = max((a for a in report.areas if a.horizontal), key=lambda a: a.area_m2)
    assert report.leni.area_m2 == grid.area_m2
    assert f"calculation area {grid.label}" in report.leni.area_label
    assert "no floor area was stated" in report.leni.area_label


def _box(x0, x1, y0, y1, z0, z1):
    """A closed box as inline geometry (12 triangles, outward)."""
    v = np.array([[x, y, z] for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)], float)
    faces = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4),
             (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)]
    return v, np.array(faces)


def _mesh(name, parts):
    verts, tris, offset = [], [], 0
    for v, t in parts:
        verts.append(v)
        tris.append(t + offset)
        offset += len(v)
    return Mesh(name, name, "m", "diffuse", 0.5, np.concatenate(verts), np.concatenate(tris))


def test_a_door_does_not_let_the_room_out_but_a_missing_wall_does():
    # A 0.2 m slab under a 5 × 4 m room with 0.2 m walls outside it; the south wall has a
    # door 1 m wide and 2.1 m high (the lintel above it closes the plan).
    slab = _mesh("slab", [_box(-0.2, 5.2, -0.2, 4.2, -0.2, 0.0)])
    north = _box(-0.2, 5.2, 4.0, 4.2, 0.0, 3.0)
    east, west = _box(5.0, 5.2, 0.0, 4.0, 0.0, 3.0), _box(-0.2, 0.0, 0.0, 4.0, 0.0, 3.0)
    south = [_box(-0.2, 2.0, -0.2, 0.0, 0.0, 3.0), _box(3.0, 5.2, -0.2, 0.0, 0.0, 3.0),
             _box(2.0, 3.0, -0.2, 0.0, 2.1, 3.0)]
    walls = _mesh("walls", [north, east, west] + south)
    level = Level(0.0, 1.0)
    area = room_floor_area([slab, walls], [walls], level, [(2.5, 2.0)])
    assert area == pytest.approx(20.0, abs=0.02)
    # Two grids in the same room: the room once.
    assert room_floor_area([slab, walls], [walls], level, [(1, 1), (4, 3)]) == area
    open_room = _mesh("walls", [north, east] + south)  # no west wall: the floor runs out
    assert room_floor_area([slab, open_room], [open_room], level, [(2.5, 2.0)]) is None
    # A point outside the floor: no room.
    assert room_floor_area([slab, walls], [walls], level, [(9.0, 9.0)]) is None
    # Turned 30° off the axes: within a fifth of a 20 mm cell times the walls' 18 m.
    c, s = np.cos(np.radians(30)), np.sin(np.radians(30))
    turn = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    slab_t, walls_t = (Mesh(m.name, m.label, m.material, m.kind, m.reflectance,
                            m.vertices @ turn.T, m.triangles) for m in (slab, walls))
    centre = (turn @ [2.5, 2.0, 0.0])[:2]
    assert room_floor_area([slab_t, walls_t], [walls_t], level, [tuple(centre)]) == \
        pytest.approx(20.0, abs=0.2 * 0.02 * 18)


# --- power from the photometric file ------------------------------------------------------------

def test_power_from_the_file_is_scaled_with_the_luminaires_flux():
    # The file: 3600 lm lamp, 36 W. The scene asks for 2160 lm maintained at MF 0.8, i.e.
    # 2700 lm initial: 0.75 of the file's flux, so 27 W.
    scene, data, results = _workbench(flux_lm=2160.0)
    report = build(data, results, scene_path=scene, date=DATE)
    (row,) = report.luminaires
    assert row.power_scale == pytest.approx(0.75, rel=1e-12)
    assert row.power_w == pytest.approx(27.0, rel=1e-12) and row.power_from_file
    assert report.total_power_w == pytest.approx(6 * 27.0, rel=1e-12)
    html = render_html(data, results, scene_path=scene, date=DATE)
    assert "36 W × 0.75" in html and "scaled by their ratio" in html


def test_power_from_the_file_at_its_own_flux_is_as_stated():
    scene, results = fixture("workbench")  # 2880 lm at MF 0.8: the file's 3600 lm
    (row,) = build(scene, results, date=DATE).luminaires
    assert row.power_scale == 1.0 and row.power_w == 36.0
    assert "scaled by their ratio" not in render_html(scene, results, date=DATE)
