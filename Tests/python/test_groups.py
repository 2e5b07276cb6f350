"""Luminaire groups from Python and the CLI (docs/statistics.md, "Groups"): results list the
groups, `--contributions` / ``contributions=True`` adds each group's part, and
``lightsolver rescale`` / ``lightsolver.rescale`` dim groups without tracing; every document
follows docs/schemas/results.schema.json."""
import json
import math
import subprocess

import jsonschema
import pytest

import lightsolver
from conftest import SOURCE_DIR, without_run_facts

SCHEMA = json.loads((SOURCE_DIR / "docs" / "schemas" / "results.schema.json").read_text())
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA)
CELL_ARRAYS = ("cells_lux", "cells_ci_low_lux", "cells_ci_high_lux", "cells_hits")


def plain(results: dict, timings: bool = False) -> dict:
    """A results dict without the numpy arrays the module adds (and the timings, with the
    provenance's run facts, unless asked)."""
    out = {k: v for k, v in results.items()
           if k != "targets" and (timings or k != "seconds")}
    out["targets"] = [{k: v for k, v in t.items() if k not in CELL_ARRAYS}
                      for t in results["targets"]]
    return out if timings else without_run_facts(out)


def schema_errors(document: dict) -> list:
    return [f"{'/'.join(map(str, e.absolute_path))}: {e.message}"
            for e in VALIDATOR.iter_errors(document)]


def run_cli(cli, *args) -> subprocess.CompletedProcess:
    return subprocess.run([cli, *map(str, args)], capture_output=True, text=True, timeout=120)


def test_cli_contributions_and_rescale(cli, room_scene, tmp_path):
    traced, dimmed = tmp_path / "r.json", tmp_path / "d.json"
    r = run_cli(cli, "run", room_scene, "--photons", 100000, "--seed", 3, "--backend", "embree",
                "--contributions", "--quiet", "--out", traced)
    assert r.returncode == 0, r.stderr
    doc = json.loads(traced.read_text())
    assert schema_errors(doc) == []
    names = [g["name"] for g in doc["groups"]]
    assert names == [f"panel {i}" for i in range(1, 5)]  # ungrouped: one group per luminaire
    assert sum(g["photons"] for g in doc["groups"]) == doc["photons"]
    r = run_cli(cli, "rescale", traced, "--dim", "panel 1=0", "--dim", "panel 2=0.5",
                "--out", dimmed)
    assert r.returncode == 0, r.stderr
    new = json.loads(dimmed.read_text())
    assert schema_errors(new) == []
    assert new["rescaled"] == {"panel 1": 0.0, "panel 2": 0.5, "panel 3": 1.0, "panel 4": 1.0}
    assert new["total_flux_lm"] == pytest.approx(doc["total_flux_lm"] * 2.5 / 4)
    for old_t, new_t in zip(doc["targets"], new["targets"]):
        parts = old_t["contributions"]
        expected = (0.5 * parts["panel 2"]["illuminance_lux"] +
                    parts["panel 3"]["illuminance_lux"] + parts["panel 4"]["illuminance_lux"])
        assert new_t["mean_lux"] == pytest.approx(expected, rel=1e-12)
        assert new_t["ci_low_lux"] <= new_t["mean_lux"] <= new_t["ci_high_lux"]
        assert new_t["contributions"]["panel 1"]["illuminance_lux"] == 0.0


def test_cli_rescale_errors(cli, room_scene, tmp_path):
    traced, plain_run = tmp_path / "r.json", tmp_path / "p.json"
    assert run_cli(cli, "run", room_scene, "--photons", 20000, "--quiet", "--contributions",
                   "--out", traced).returncode == 0
    assert run_cli(cli, "run", room_scene, "--photons", 20000, "--quiet",
                   "--out", plain_run).returncode == 0
    for args, message in [(["--dim", "hall=0.5"], 'no luminaire group "hall"'),
                          (["--dim", "panel 1=-1"], "finite number >= 0"),
                          (["--dim", "panel 1=nan"], "finite number >= 0"),
                          (["--dim", "panel 1"], "GROUP=FACTOR"),
                          (["--dim", "panel 1=x"], "not a number")]:
        r = run_cli(cli, "rescale", traced, *args)
        assert r.returncode == 1 and message in r.stderr, (args, r.stderr)
    r = run_cli(cli, "rescale", plain_run, "--dim", "panel 1=0")
    assert r.returncode == 1 and "--contributions" in r.stderr


def test_python_rescale_is_the_cli_rescale(cli, room_scene, tmp_path):
    scene = lightsolver.load_scene(str(room_scene))
    traced = lightsolver.solve(scene, photons=60000, seed=4, backend="embree", contributions=True)
    assert schema_errors(plain(traced, timings=True)) == []
    dimmed = lightsolver.rescale(traced, {"panel 3": 0.25})
    assert dimmed["rescaled"]["panel 3"] == 0.25
    assert dimmed["targets"][1]["cells_lux"].shape == traced["targets"][1]["cells_lux"].shape
    path, out = tmp_path / "r.json", tmp_path / "d.json"
    assert run_cli(cli, "run", room_scene, "--photons", 60000, "--seed", 4, "--backend",
                   "embree", "--contributions", "--quiet", "--out", path).returncode == 0
    assert run_cli(cli, "rescale", path, "--dim", "panel 3=0.25", "--out", out).returncode == 0
    assert plain(dimmed) == plain(json.loads(out.read_text()))
    # Factor 1 everywhere: the traced targets, bit for bit.
    assert plain(lightsolver.rescale(traced, {}))["targets"] == plain(traced)["targets"]


@pytest.mark.parametrize("factors,message", [({"hall": 1.0}, "no luminaire group"),
                                             ({"panel 1": -0.1}, "finite number >= 0"),
                                             ({"panel 1": math.nan}, "finite number >= 0"),
                                             ({"panel 1": math.inf}, "finite number >= 0")])
def test_python_rescale_errors(room_scene, factors, message):
    traced = lightsolver.solve(lightsolver.load_scene(str(room_scene)), photons=20000,
                               contributions=True)
    with pytest.raises(lightsolver.InputError, match=message):
        lightsolver.rescale(traced, factors)


def test_python_rescale_needs_contributions(room_scene):
    traced = lightsolver.solve(lightsolver.load_scene(str(room_scene)), photons=20000)
    with pytest.raises(ValueError, match="--contributions"):
        lightsolver.rescale(traced, {"panel 1": 0.5})


def test_groups_from_the_scene_and_observer_glare_rescaled(room_scene):
    """Explicit groups; an observer's UGR after dimming every group by k moves by exactly
    8 log10(k): every luminance by k (squared in the sum), L_b by k."""
    scene = lightsolver.load_scene(str(room_scene))
    doc = json.loads((room_scene).read_text())
    for entry in doc["luminaires"]:
        entry["group"] = "left" if entry["name"] in ("panel 1", "panel 2") else "right"
    doc["targets"].append({"name": "eye", "type": "observer", "position": [1.0, 1.0, 1.2],
                           "view_direction": [1, 0, 0]})
    scene = lightsolver.scene_from_json(json.dumps(doc), str(room_scene.parent))
    traced = lightsolver.solve(scene, photons=100000, seed=1, contributions=True)
    assert [g["name"] for g in traced["groups"]] == ["left", "right"]
    assert traced["groups"][0]["luminaires"] == ["panel 1", "panel 2"]
    eye = traced["targets"][-1]
    assert eye["ugr"] is not None
    same = lightsolver.rescale(traced, {})["targets"][-1]
    assert same["ugr"] == eye["ugr"] and same["luminaires"] == eye["luminaires"]
    k = 0.5
    dimmed = lightsolver.rescale(traced, {"left": k, "right": k})["targets"][-1]
    assert schema_errors(plain(lightsolver.rescale(traced, {"left": k, "right": k}), True)) == []
    assert dimmed["ugr"] == pytest.approx(eye["ugr"] + 8 * math.log10(k), abs=1e-9)
    assert dimmed["background_luminance_cd_m2"] == pytest.approx(
        k * eye["background_luminance_cd_m2"], rel=1e-12)


def test_contributions_from_the_scene_settings(room_scene):
    doc = json.loads(room_scene.read_text())
    doc.setdefault("settings", {})["contributions"] = True
    scene = lightsolver.scene_from_json(json.dumps(doc), str(room_scene.parent))
    assert scene.contributions
    traced = lightsolver.solve(scene, photons=20000)
    assert all("contributions" in t for t in traced["targets"])
    scene.contributions = False
    assert all("contributions" not in t for t in lightsolver.solve(scene, photons=20000)["targets"])
