"""Per-cell accuracy (`--accuracy X --per-cell`) and `lightsolver study` (what accuracy costs,
shown), on a closed form: an isotropic point source over a black plane, whose every grid cell's
mean illuminance is known exactly (Phi / 4 pi times the cell's solid angle / its area)."""
import csv
import io
import json
import math
import subprocess
from pathlib import Path
from typing import Dict, List

import lightsolver
import numpy as np
import pytest
from test_results_schema import errors as schema_errors

FLUX_LM = 10_000.0
HEIGHT_M = 1.0
Z95 = 1.959963984540054  # two-sided 95 % normal quantile
K = 4.5  # sigma tolerance of the closed-form checks: P(any of 100 cells off) ~ 7e-4 per run


def run(cli, *args):
    return subprocess.run([cli, *args], capture_output=True, text=True, timeout=120)


def rectangle_solid_angle(x1: float, x2: float, y1: float, y2: float, h: float) -> float:
    """Solid angle of the rectangle [x1, x2] x [y1, y2] in z = 0 seen from (0, 0, h)."""
    def f(x: float, y: float) -> float:
        return math.atan(x * y / (h * math.sqrt(x * x + y * y + h * h)))
    return f(x2, y2) - f(x1, y2) - f(x2, y1) + f(x1, y1)


def exact_cells(corner, size_m: float, n: int) -> np.ndarray:
    """Mean lux of each cell (row by row, shape (n, n)) under the source at (0, 0, HEIGHT_M)."""
    cell = size_m / n
    out = np.empty((n, n))
    for iv in range(n):
        for iu in range(n):
            x1, y1 = corner[0] + iu * cell, corner[1] + iv * cell
            omega = rectangle_solid_angle(x1, x1 + cell, y1, y1 + cell, HEIGHT_M)
            out[iv, iu] = FLUX_LM / (4 * math.pi) * omega / cell ** 2
    return out


def quad(name: str, material: str, x1, x2, y1, y2, z) -> Dict:
    return {"name": name, "material": material,
            "vertices": [[x1, y1, z], [x2, y1, z], [x2, y2, z], [x1, y2, z]],
            "triangles": [[0, 1, 2], [0, 2, 3]]}


def closed_form_scene(occluder: bool = False, per_cell_setting: bool = False) -> Dict:
    """A 2 x 2 m grid of 10 x 10 cells on a black floor 1 m under a point source; with
    `occluder`, a black plate at half height shadows the grid's corner x, y < -0.5 m fully."""
    meshes = [quad("floor", "black", -5, 5, -5, 5, -0.01)]
    if occluder:
        meshes.append(quad("plate", "black", -2.0, -0.25, -2.0, -0.25, 0.5))
    scene = {"format": "lightsolver.scene/1", "materials": {"black": {"type": "diffuse",
                                                                      "reflectance": 0.0}},
             "meshes": meshes,
             "luminaires": [{"name": "lamp", "type": "point", "position": [0, 0, HEIGHT_M],
                             "flux_lm": FLUX_LM}],
             "targets": [{"name": "floor grid", "type": "grid", "corner": [-1, -1, 0],
                          "edge1": [2, 0, 0], "edge2": [0, 2, 0], "cells": [10, 10]}]}
    # These tests check photon statistics (per-cell stopping, errors as N^-1/2): photons alone.
    # With next-event estimation (the default) the black floor's light would be the shadow
    # rays' direct part alone, which no photon moves.
    scene["settings"] = {"next_event": "off"}
    if per_cell_setting:
        scene["settings"]["accuracy_per_cell"] = True
    return scene


@pytest.fixture()
def scene_file(tmp_path) -> Path:
    path = tmp_path / "point_over_black.json"
    path.write_text(json.dumps(closed_form_scene()))
    return path


def half_widths(grid: Dict) -> np.ndarray:
    return (grid["cells_ci_high_lux"] - grid["cells_ci_low_lux"]) / 2


def test_per_cell_accuracy_meets_its_bound_in_every_cell(scene_file):
    scene = lightsolver.load_scene(str(scene_file))
    goal = 0.05
    r = lightsolver.solve(scene, target_accuracy=goal, accuracy_per_cell=True, seed=3,
                          photons=100_000_000)
    assert r["stop_reason"] == "accuracy" and r["accuracy_met"] and r["accuracy_per_cell"]
    grid = r["targets"][0]
    lux, hw = grid["cells_lux"], half_widths(grid)
    # Every cell is lit (the corners get ~19 % of the centre), so the rule is the plain one.
    assert np.all(hw / lux <= goal)
    # ... and the intervals are honest: every cell within K sigma of the closed form.
    exact = exact_cells([-1, -1], 2.0, 10)
    sigma = hw / Z95
    assert np.all(np.abs(lux - exact) <= K * sigma), np.max(np.abs(lux - exact) / sigma)
    assert np.all(np.abs(lux - exact) / exact <= K / Z95 * goal)
    # The same goal on the target mean stops far earlier, with cells far wider than the goal:
    # why the per-cell mode exists.
    mean_only = lightsolver.solve(scene, target_accuracy=goal, seed=3, photons=100_000_000)
    assert not mean_only["accuracy_per_cell"]
    assert mean_only["photons"] < r["photons"] / 10
    g = mean_only["targets"][0]
    assert np.max(half_widths(g) / g["cells_lux"]) > 3 * goal


def test_cells_in_full_shadow_are_judged_against_one_percent_of_the_grid_mean(tmp_path):
    path = tmp_path / "shadowed.json"
    path.write_text(json.dumps(closed_form_scene(occluder=True, per_cell_setting=True)))
    scene = lightsolver.load_scene(str(path))
    goal = 0.1
    # The scene's settings.accuracy_per_cell turns the mode on.
    r = lightsolver.solve(scene, target_accuracy=goal, seed=5, photons=50_000_000)
    assert r["accuracy_per_cell"] and r["stop_reason"] == "accuracy"
    grid = r["targets"][0]
    lux, hw, hits = grid["cells_lux"], half_widths(grid), grid["cells_hits"]
    dark = hits == 0
    # The plate casts its shadow on x, y < -0.5 m: the lower-left 2 x 2 cells see no light.
    assert dark[:2, :2].all() and dark.sum() >= 4
    # Lit cells: relative; dark cells: absolute, against 1 % of the grid's mean.
    floor = 0.01 * grid["mean_lux"]
    assert np.all(hw[~dark] / np.maximum(lux[~dark], floor) <= goal)
    assert np.all(hw[dark] <= goal * floor)
    assert np.all(hw[dark] > 0)  # Wilson: a zero count still has an upper bound


def test_per_cell_flag_of_the_cli(cli, scene_file, tmp_path):
    out = tmp_path / "r.json"
    r = run(cli, "run", str(scene_file), "--accuracy", "0.1", "--per-cell", "--seed", "2",
            "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert "accuracy goal ±10 % per cell met" in r.stdout
    res = json.loads(out.read_text())
    assert res["accuracy_per_cell"] and res["accuracy_met"]
    assert max((c["ci_high_lux"] - c["ci_low_lux"]) / 2 / c["lux"]
               for c in res["targets"][0]["cells"]) <= 0.1
    assert schema_errors(res) == []
    r = run(cli, "run", str(scene_file), "--per-cell")
    assert r.returncode != 0 and "--accuracy" in r.stderr


def test_accuracy_per_cell_setting_must_be_a_boolean():
    scene = closed_form_scene()
    scene["settings"] = {"accuracy_per_cell": 1}
    check = lightsolver.check_scene_json(json.dumps(scene))
    assert check["errors"] and check["errors"][0]["field"] == "settings.accuracy_per_cell"


def closed_form_reference(cli, scene_file: Path, path: Path) -> Path:
    """A results file of the scene whose numbers are the closed form (exact: zero width)."""
    r = run(cli, "run", str(scene_file), "--photons", "10000", "--quiet", "--out", str(path))
    assert r.returncode == 0, r.stderr
    res = json.loads(path.read_text())
    exact = exact_cells([-1, -1], 2.0, 10).ravel()
    grid = res["targets"][0]
    for cell, e in zip(grid["cells"], exact):
        cell.update(lux=e, ci_low_lux=e, ci_high_lux=e)
    mean = float(exact.mean())
    grid.update(mean_lux=mean, ci_low_lux=mean, ci_high_lux=mean)
    path.write_text(json.dumps(res))
    return path


def star_rows(csv_text: str) -> List[Dict[str, str]]:
    return [row for row in csv.DictReader(io.StringIO(csv_text)) if row["target"] == "*"]


def test_study_against_the_closed_form(cli, scene_file, tmp_path):
    ref = closed_form_reference(cli, scene_file, tmp_path / "exact.json")
    csv_path, json_path, png = tmp_path / "s.csv", tmp_path / "s.json", tmp_path / "s.png"
    r = run(cli, "study", str(scene_file), "--max-photons", "1280000", "--seed", "4",
            "--reference", str(ref), "--csv", str(csv_path), "--json", str(json_path),
            "--plot", str(png))
    assert r.returncode == 0, r.stderr
    rows = star_rows(csv_path.read_text())
    photons = [int(row["photons"]) for row in rows]
    assert photons == [10_000 * 2 ** k for k in range(8)]  # doubling, one run
    seconds = [float(row["seconds"]) for row in rows]
    assert seconds == sorted(seconds)
    errors = np.array([float(row["mean_relative_error"]) for row in rows])
    widths = np.array([float(row["mean_relative_half_width"]) for row in rows])
    # Errors shrink as N^-1/2. Each row's mean error averages |Z| over 100 cells: relative sd
    # sqrt(pi/2 - 1)/10 = 0.0756 in log; the rows are nested (positively correlated), so the
    # slope's sd is at most that of two independent end points, 0.0756 * sqrt(2) / ln(128).
    slope = np.polyfit(np.log(photons), np.log(errors), 1)[0]
    slope_sd = math.sqrt(math.pi / 2 - 1) / 10 * math.sqrt(2) / math.log(128)
    assert abs(slope + 0.5) <= 5 * slope_sd, slope
    width_slope = np.polyfit(np.log(photons), np.log(widths), 1)[0]
    # The widths' own noise is far smaller (largest deviation over 40 seeds: 0.02).
    assert abs(width_slope + 0.5) <= 0.05
    # Honest intervals: mean |error| / mean half-width = E|Z| / z = 0.407 (same 0.0756 spread).
    ratio = errors[-1] / widths[-1]
    assert abs(ratio / (math.sqrt(2 / math.pi) / Z95) - 1) <= 4 * 0.0756, ratio
    study = json.loads(json_path.read_text())
    assert study["format"] == "lightsolver.study/1" and study["reference"]["file"] == str(ref)
    assert [row["photons"] for row in study["rows"]] == photons
    assert study["rows"][-1]["all"]["mean_relative_error"] == pytest.approx(errors[-1],
                                                                           rel=1e-9)
    # The goals: from the fit of the worst cell's width, marked where extrapolated.
    goals = {g["accuracy"]: g for g in study["goals"]}
    assert list(goals) == [0.1, 0.05, 0.02, 0.01, 0.005]
    c = study["fit"]["coefficient"]
    for g in goals.values():
        assert g["photons"] == pytest.approx((c / g["accuracy"]) ** 2, rel=1e-12)
        assert g["extrapolated"] == (g["photons"] > photons[-1])
    assert goals[0.005]["extrapolated"] and "extrapolated beyond the last checkpoint" in r.stdout
    # The fit agrees with the last row's worst width within the worst cell's noise.
    last_worst = float(rows[-1]["worst_relative_half_width"])
    assert c / math.sqrt(photons[-1]) == pytest.approx(last_worst, rel=0.1)
    # The plot: a PNG that is not blank.
    import matplotlib.image
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    pixels = matplotlib.image.imread(str(png))
    assert pixels.shape[0] > 300 and pixels.shape[1] > 400
    assert (pixels[..., :3].std(axis=(0, 1)) > 0.05).all()  # lines, not one colour


def test_study_rows_are_checkpoints_of_one_run(room_scene):
    scene = lightsolver.load_scene(str(room_scene))
    s = lightsolver.study(scene, max_photons=40_000, seed=9)
    assert [row["photons"] for row in s["rows"]] == [10_000, 20_000, 40_000]
    assert s["results"]["photons"] == 40_000 and s["reference"] is None
    for row in s["rows"]:
        plain = lightsolver.solve(scene, photons=row["photons"], seed=9)
        for t, p in zip(row["targets"], plain["targets"]):
            assert t["em_lux"] == p["mean_lux"] and t["em_ci_high_lux"] == p["ci_high_lux"]
            if p["type"] == "grid":
                assert t["emin_lux"] == p["min_lux"] and t["u0"] == p["uniformity"]
                rel = half_widths(p) / p["cells_lux"]  # every room cell is lit
                assert t["worst_relative_half_width"] == pytest.approx(rel.max(), rel=1e-12)
                assert t["mean_relative_half_width"] == pytest.approx(rel.mean(), rel=1e-12)
        assert row["all"]["mean_relative_error"] is None  # no reference, no error
    assert star_rows(s["csv"])[0]["photons"] == "10000"


def test_study_against_a_long_run_and_its_bad_references(cli, scene_file, room_scene, tmp_path):
    long_run = tmp_path / "long.json"
    assert run(cli, "run", str(scene_file), "--photons", "2000000", "--seed", "8", "--quiet",
               "--out", str(long_run)).returncode == 0
    r = run(cli, "study", str(scene_file), "--max-photons", "40000", "--reference", str(long_run))
    assert r.returncode == 0, r.stderr
    assert "mean err [%]" in r.stdout
    # A reference that does not exist, or is from another scene: clear errors, nothing traced.
    missing = tmp_path / "nowhere.json"
    r = run(cli, "study", str(scene_file), "--reference", str(missing))
    assert r.returncode == 1 and str(missing) in r.stderr and "photons" not in r.stdout
    room_results = tmp_path / "room.json"
    assert run(cli, "run", str(room_scene), "--photons", "10000", "--quiet",
               "--out", str(room_results)).returncode == 0
    r = run(cli, "study", str(scene_file), "--reference", str(room_results))
    assert r.returncode == 1 and str(room_results) in r.stderr
    assert "another scene" in r.stderr and "photons" not in r.stdout
    with pytest.raises(lightsolver.InputError, match="another scene"):
        lightsolver.study(lightsolver.load_scene(str(scene_file)), max_photons=10_000,
                          reference=str(room_results))
    not_results = tmp_path / "scene_as_reference.json"
    not_results.write_text(scene_file.read_text())
    r = run(cli, "study", str(scene_file), "--reference", str(not_results))
    assert r.returncode == 1 and "not a results file" in r.stderr


def test_study_checks_its_outputs_before_tracing(cli, scene_file, tmp_path):
    r = run(cli, "study", str(scene_file), "--max-photons", "9999")
    assert r.returncode == 1 and "--max-photons: must be >= 10000" in r.stderr
    r = run(cli, "study", str(scene_file), "--plot", str(tmp_path / "plot.pdf"))
    assert r.returncode == 1 and "plot.pdf" in r.stderr and ".png or .svg" in r.stderr
    r = run(cli, "study", str(scene_file), "--csv", str(tmp_path / "no" / "dir" / "s.csv"))
    assert r.returncode == 1 and "s.csv" in r.stderr and "photons" not in r.stdout
    svg = tmp_path / "plot.svg"
    r = run(cli, "study", str(scene_file), "--max-photons", "20000", "--plot", str(svg))
    assert r.returncode == 0, r.stderr
    assert svg.read_text().lstrip().startswith("<?xml") and "<path" in svg.read_text()


def test_study_and_cost_trace_every_checkpoint_in_a_scene_that_decides(tmp_path):
    """A scene whose settings decide its requirements (the workbench's default) is still
    studied to its last checkpoint: deciding would stop at the first decided look."""
    doc = closed_form_scene()
    doc["targets"][0]["requirements"] = {"em_lux": 1.0}  # far below the truth: decided at once
    doc["settings"] = dict(doc["settings"], decide=True)
    path = tmp_path / "decides.json"
    path.write_text(json.dumps(doc))
    scene = lightsolver.load_scene(str(path))
    assert lightsolver.solve(scene, photons=160_000)["stop_reason"] == "decided"
    study = lightsolver.study(scene, max_photons=80_000, seed=9)
    assert [row["photons"] for row in study["rows"]] == [10_000, 20_000, 40_000, 80_000]
    plain = dict(doc, settings={"next_event": "off"})
    path.write_text(json.dumps(plain))
    without = lightsolver.cost(lightsolver.load_scene(str(path)), max_photons=80_000, seed=9)
    cost = lightsolver.cost(scene, max_photons=80_000, seed=9)
    assert [r["photons"] for r in cost["rows"]] == [r["photons"] for r in without["rows"]]
