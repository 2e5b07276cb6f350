"""Rescaling observer grids from Python and the CLI (docs/glare.md, "Rescaling an observer
grid"): factor 1 gives the traced grid bit for bit, every group dimmed by k moves every point's
UGR by exactly 8 log10(k) (L by k, squared in the sum; L_b by k), the CLI and the module agree,
and the documents follow docs/schemas/results.schema.json."""
import json
import math

import pytest

import lightsolver
from test_groups import plain, run_cli, schema_errors

EYES = {"name": "eyes", "type": "observer_grid", "positions": [[0.5, 0.5, 1.2], [3.0, 2.0, 1.2]],
        "view_step_deg": 90, "requirements": {"ugr_max": 19}}


def untimed(results: dict) -> list:
    """The targets without the numpy arrays and without an undecided verdict's seconds (a
    timing: the rescale prices it at the run's overall rate)."""
    targets = plain(results)["targets"]
    for target in targets:
        for verdict in target.get("verdicts", {}).values():
            verdict.get("to_decide", {}).pop("seconds", None)
    return targets


def grouped_scene(room_scene) -> dict:
    """The room with its panels in two groups and a grid of seated eyes."""
    doc = json.loads(room_scene.read_text())
    for entry in doc["luminaires"]:
        entry["group"] = "left" if entry["name"] in ("panel 1", "panel 2") else "right"
    doc["targets"].append(dict(EYES))
    return doc


def test_python_rescale_of_an_observer_grid(room_scene):
    doc = grouped_scene(room_scene)
    scene = lightsolver.scene_from_json(json.dumps(doc), str(room_scene.parent))
    traced = lightsolver.solve(scene, photons=100000, seed=2, backend="embree", contributions=True)
    assert schema_errors(plain(traced, timings=True)) == []
    eyes = traced["targets"][-1]
    terms = eyes["observer_grid"]["glare_terms"]
    assert len(terms["status"]) == len(terms["terms"]) == 8
    assert all(len(s) == len(doc["luminaires"]) for s in terms["status"])
    assert len(eyes["contributions"]["left"]["points"]) == 8
    same = lightsolver.rescale(traced, {})
    assert untimed(same) == untimed(traced)
    k = 0.5
    dimmed = lightsolver.rescale(traced, {"left": k, "right": k})
    assert schema_errors(plain(dimmed, timings=True)) == []
    grid, new = eyes["observer_grid"], dimmed["targets"][-1]["observer_grid"]
    for row, new_row in zip(grid["ugr"], new["ugr"]):
        for u, v in zip(row, new_row):
            assert (u is None) == (v is None)
            if u is not None:
                assert v == pytest.approx(u + 8 * math.log10(k), abs=1e-9)
    assert dimmed["targets"][-1]["ugr"] == pytest.approx(eyes["ugr"] + 8 * math.log10(k),
                                                         abs=1e-9)
    off = lightsolver.rescale(traced, {"left": 0})["targets"][-1]
    assert all(not part["counted"] for part in off["luminaires"][:2])


def test_cli_rescale_of_an_observer_grid(cli, room_scene, tmp_path):
    scene, traced, dimmed = tmp_path / "s.json", tmp_path / "r.json", tmp_path / "d.json"
    doc = grouped_scene(room_scene)  # its meshes are inline: it may move
    scene.write_text(json.dumps(doc))
    r = run_cli(cli, "run", scene, "--photons", 50000, "--seed", 5, "--backend", "embree",
                "--contributions", "--quiet", "--out", traced)
    assert r.returncode == 0, r.stderr
    r = run_cli(cli, "rescale", traced, "--dim", "right=0.25", "--out", dimmed)
    assert r.returncode == 0, r.stderr
    new = json.loads(dimmed.read_text())
    assert schema_errors(new) == []
    assert new["targets"][-1]["observer_grid"]["glare_terms"]["luminaires"] == [
        entry["name"] for entry in doc["luminaires"]]
    module = lightsolver.rescale(json.loads(traced.read_text()), {"right": 0.25})
    assert plain(module)["targets"] == plain(new)["targets"]
