"""One results contract: the CLI's results file and ``lightsolver.solve()`` both follow
docs/schemas/results.schema.json and agree field by field for the same scene and seed."""
import copy
import json
import subprocess

import jsonschema
import pytest

import lightsolver
from conftest import SOURCE_DIR, without_run_facts

SCHEMA = json.loads((SOURCE_DIR / "docs" / "schemas" / "results.schema.json").read_text())
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA)
#: Added by the Python module beside the layout (numpy), not part of the JSON contract.
CELL_ARRAYS = ("cells_lux", "cells_ci_low_lux", "cells_ci_high_lux", "cells_hits")
TIMINGS = ("seconds",)  # the only fields that may differ between two identical runs


def plain(results: dict) -> dict:
    """``solve()``'s dict without the numpy arrays it adds beside the layout."""
    out = {k: v for k, v in results.items() if k != "targets"}
    out["targets"] = [{k: v for k, v in t.items() if k not in CELL_ARRAYS}
                      for t in results["targets"]]
    return out


def errors(document: dict) -> list:
    return [f"{'/'.join(map(str, e.absolute_path))}: {e.message}"
            for e in VALIDATOR.iter_errors(document)]


def cli_results(cli, scene, tmp_path, *args) -> dict:
    out = tmp_path / "r.json"
    r = subprocess.run([cli, "run", str(scene), "--quiet", "--out", str(out), *args],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    return json.loads(out.read_text())


@pytest.mark.parametrize("photons,accuracy", [(200000, None), (400000, 0.05)])
def test_cli_file_and_solve_agree_field_by_field(cli, room_scene, tmp_path, photons, accuracy):
    extra = ["--accuracy", str(accuracy)] if accuracy else []
    from_cli = cli_results(cli, room_scene, tmp_path, "--photons", str(photons), "--seed", "5",
                           "--backend", "embree", *extra)
    from_py = plain(lightsolver.solve(lightsolver.load_scene(str(room_scene)), photons=photons,
                                      seed=5, backend="embree", target_accuracy=accuracy))
    assert errors(from_cli) == []
    assert errors(from_py) == []
    for doc in (from_cli, from_py):
        for key in TIMINGS:
            doc.pop(key)
    assert from_cli["provenance"]["command"].split()[1:3] == ["run", str(room_scene)]
    assert from_py["provenance"]["command"].startswith("python: lightsolver.solve")
    # every number to the bit, every key, every warning, the provenance but when and how it ran
    assert without_run_facts(from_py) == without_run_facts(from_cli)


def test_python_grids_carry_the_layout_and_numpy_beside_it(room_scene):
    r = lightsolver.solve(lightsolver.load_scene(str(room_scene)), photons=50000, seed=2)
    grid = next(t for t in r["targets"] if t["type"] == "grid")
    nu, nv = grid["cells_uv"]
    assert len(grid["cells"]) == nu * nv
    assert grid["cells_lux"].shape == (nv, nu)
    assert [c["lux"] for c in grid["cells"]] == grid["cells_lux"].ravel().tolist()
    assert [c["hits"] for c in grid["cells"]] == grid["cells_hits"].ravel().tolist()


def test_schema_rejects_what_the_contract_forbids(cli, room_scene, tmp_path):
    good = cli_results(cli, room_scene, tmp_path, "--photons", "20000")
    assert errors(good) == []
    for path, value in [(("format",), "lightsolver.results/2"), (("stop_reason",), "tired"),
                        (("targets", 0, "mean_lux"), -1.0), (("photons",), 1.5),
                        (("targets", 1, "cells", 0, "hits"), "many"),
                        (("unknown_field",), 1), (("targets", 0, "cells_uv"), [2, 2])]:
        bad = copy.deepcopy(good)
        node = bad
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value
        assert errors(bad), f"the schema accepted {path} = {value!r}"
    bad = copy.deepcopy(good)
    del bad["targets"][1]["cells"]
    assert errors(bad), "a grid without cells"


def room_with_requirements(room_scene, tmp_path, **settings) -> str:
    """Examples/room (inline geometry) with requirements on its desk (Em) and workplane (an
    EN 12464-1 task plus Ud), and a luminaire's power."""
    scene = json.loads(room_scene.read_text())
    for target in scene["targets"]:
        if target["name"] == "desk top":
            target["requirements"] = {"em_lux": 300}
        if target["name"] == "workplane":
            target["task"] = "office-writing"
            target["requirements"] = {"ud": 0.5}
    scene["luminaires"][0]["power_w"] = 36.0
    scene["settings"].update(settings)
    path = tmp_path / "requirements.json"
    path.write_text(json.dumps(scene))
    return str(path)


@pytest.mark.parametrize("decide", [False, True])
def test_verdicts_follow_the_contract_in_cli_and_solve(cli, room_scene, tmp_path, decide):
    scene = room_with_requirements(room_scene, tmp_path)
    extra = ["--decide"] if decide else []
    from_cli = cli_results(cli, scene, tmp_path, "--photons", "300000", "--seed", "3",
                           "--backend", "embree", *extra)
    from_py = plain(lightsolver.solve(lightsolver.load_scene(scene), photons=300000, seed=3,
                                      backend="embree", decide=decide or None))
    assert errors(from_cli) == []
    assert errors(from_py) == []
    for doc in (from_cli, from_py):
        for key in TIMINGS:
            doc.pop(key)
        # to_decide's seconds come from the tracing rate: a timing too.
        for target in doc["targets"]:
            for verdict in target.get("verdicts", {}).values():
                verdict.get("to_decide", {}).pop("seconds", None)
    assert without_run_facts(from_py) == without_run_facts(from_cli)
    assert from_cli["decide"] is decide
    desk, grid, floor = from_cli["targets"]
    assert set(desk["verdicts"]) == {"em"}
    assert set(grid["verdicts"]) == {"em", "u0", "ud"}
    assert grid["requirements"]["task"] == "office-writing"
    assert grid["requirements"]["em_lux"] == 500 and grid["requirements"]["u0"] == 0.6
    assert "EN 12464-1:2021" in grid["requirements"]["source"]
    assert "verdicts" not in floor and "requirements" not in floor
    for t in (desk, grid):
        for v in t["verdicts"].values():
            assert v["ci_low"] <= v["value"] <= v["ci_high"]
    assert grid["min_ci_low_lux"] <= grid["min_lux"] <= grid["min_ci_high_lux"]
    assert grid["uniformity_ci_low"] <= grid["uniformity"] <= grid["uniformity_ci_high"]
    assert grid["ud_ci_low"] <= grid["ud"] <= grid["ud_ci_high"]


def test_scene_decide_setting_and_requirements_in_memory():
    scene = lightsolver.Scene()
    scene.add_light("lamp", "point", position=[1, 1, 2], flux_lm=10000, power_w=80)
    scene.add_target("floor", "grid", corner=[0, 0, 0], edge1=[2, 0, 0], edge2=[0, 2, 0],
                     cells=[4, 4], task="office-writing")
    scene.add_target("dim", "grid", corner=[0, 0, 0], edge1=[2, 0, 0], edge2=[0, 2, 0],
                     cells=[2, 2], requirements={"em_lux": 100})
    assert scene.decide is False
    scene.decide = True
    r = lightsolver.solve(scene, backend="embree", photons=10**8, seed=4)
    assert errors(plain(r)) == []
    assert r["decide"] is True and r["stop_reason"] == "decided"
    assert r["photons"] < 10**8
    assert r["verdict"] == "fail"  # about 160 lx against office-writing's 500
    assert r["targets"][0]["verdicts"]["em"]["verdict"] == "fail"
    assert r["targets"][1]["verdict"] == "pass"
    with pytest.raises(lightsolver.InputError, match="unknown task"):
        scene.add_target("x", "grid", corner=[0, 0, 0], edge1=[1, 0, 0], edge2=[0, 1, 0],
                         cells=[1, 1], task="office")


def test_schema_rejects_broken_verdicts(cli, room_scene, tmp_path):
    good = cli_results(cli, room_with_requirements(room_scene, tmp_path), tmp_path, "--photons",
                       "20000")
    assert errors(good) == []
    desk, grid = good["targets"][0], good["targets"][1]
    some = next(iter(grid["verdicts"]))
    undecided = {"verdict": "undecided", "value": 1.0, "ci_low": 0.5, "ci_high": 1.5,
                 "required": 1.0, "relation": ">="}
    for mutate in [lambda d: d["targets"][1]["verdicts"][some].update(verdict="maybe"),
                   lambda d: d["targets"][1]["verdicts"][some].update(relation="<="),
                   lambda d: d["targets"][1].update(verdict="ok"),
                   lambda d: d["targets"][1]["verdicts"].update(glare=undecided),
                   lambda d: d["targets"][1]["verdicts"].update(em=undecided),  # no to_decide
                   lambda d: d["targets"][0]["verdicts"].update(u0=dict(
                       undecided, to_decide={"photons": 1, "seconds": 1})),  # u0 on a surface
                   lambda d: d["targets"][1].pop("verdicts"),
                   lambda d: d.pop("decide"),
                   lambda d: d["targets"][1].update(uniformity_ci_high=1.5),
                   lambda d: d["targets"][1]["requirements"].update(u0=0)]:
        bad = copy.deepcopy(good)
        mutate(bad)
        assert errors(bad), "the schema accepted a broken verdict"
    assert desk["verdict"] in ("pass", "fail", "undecided")


def room_with_observers(room_scene, tmp_path) -> str:
    """Examples/room with two observers (docs/glare.md): one at an office task's UGR limit,
    one with an explicit limit, and a point light the UGR must list as excluded."""
    scene = json.loads(room_scene.read_text())
    scene["luminaires"].append({"name": "spot-ish", "type": "point", "flux_lm": 50,
                                "position": [1.0, 1.0, 2.0]})
    scene["targets"] += [
        {"name": "seated", "type": "observer", "position": [0.5, 0.5, 1.2],
         "view_direction": [1, 1, 0], "task": "office-writing"},
        {"name": "standing", "type": "observer", "position": [1.0, 0.4, 1.7],
         "view_direction": [0, 1, 0], "up": [0, 0, 1], "requirements": {"ugr_max": 40}}]
    path = tmp_path / "observers.json"
    path.write_text(json.dumps(scene))
    return str(path)


def test_observer_results_follow_the_schema(cli, room_scene, tmp_path):
    r = cli_results(cli, room_with_observers(room_scene, tmp_path), tmp_path, "--photons",
                    "300000", "--seed", "2", "--backend", "embree")
    assert errors(r) == []
    seated, standing = r["targets"][-2], r["targets"][-1]
    assert seated["type"] == "observer" and seated["requirements"]["ugr_max"] == 19
    assert "em_lux" not in seated["requirements"]
    for t in (seated, standing):
        assert t["background_ci_low_cd_m2"] <= t["background_luminance_cd_m2"] \
            <= t["background_ci_high_cd_m2"]
        v = t["verdicts"]["ugr"]
        assert v["relation"] == "<="
        assert [p["name"] for p in t["luminaires"]][-1] == "spot-ish"
        assert t["luminaires"][-1]["counted"] is False
        if t["ugr"] is not None:
            assert t["ugr_ci_low"] <= t["ugr"] <= t["ugr_ci_high"]
    for mutate in [lambda t: t["verdicts"]["ugr"].update(relation=">="),
                   lambda t: t.pop("ugr"),
                   lambda t: t["verdicts"].update(em=t["verdicts"]["ugr"]),
                   lambda t: t["luminaires"][-1].pop("why_not"),
                   lambda t: t.update(type="surface")]:
        bad = copy.deepcopy(r)
        mutate(bad["targets"][-1])
        assert errors(bad), "the schema accepted a broken observer"


def test_daylight_factor_results_follow_the_schema(cli, tmp_path):
    """The side-lit example (a daylight-factor grid with EN 17037's minimum level): the CLI's
    file and solve() agree, follow the schema, and the schema refuses a DF block broken or
    misplaced."""
    scene = SOURCE_DIR / "Examples" / "daylight" / "side_lit_room.scene.json"
    r = cli_results(cli, scene, tmp_path, "--photons", "100000", "--seed", "3",
                    "--backend", "embree")
    assert errors(r) == []
    grid = r["targets"][0]
    df = grid["daylight_factor"]
    assert df["sky"] == "overcast sky" and df["outside_illuminance_lx"] == 10000
    assert len(df["cells"]) == grid["cells_uv"][0] * grid["cells_uv"][1]
    for key in ("", "min_", "p50_", "p95_"):
        value = df["mean_percent" if not key else key + "percent"]
        assert df[key + "ci_low_percent"] <= value <= df[key + "ci_high_percent"]
    assert set(grid["verdicts"]) == {"df_target", "df_minimum"}
    assert grid["verdicts"]["df_target"]["value"] == df["p50_percent"]
    assert grid["requirements"]["df_target_percent"] == pytest.approx(300 / 159)
    py = plain(lightsolver.solve(lightsolver.load_scene(str(scene)), photons=100000, seed=3,
                                 backend="embree"))
    assert py["targets"][0]["daylight_factor"] == df
    for mutate in [lambda t: t["daylight_factor"].pop("p50_percent"),
                   lambda t: t["verdicts"].update(em=t["verdicts"]["df_target"]),
                   lambda t: t["requirements"].update(em_lux=500),
                   lambda t: t["daylight_factor"]["cells"][0].update(lux=1.0),
                   lambda t: t.update(type="surface")]:
        bad = copy.deepcopy(r)
        mutate(bad["targets"][0])
        assert errors(bad), "the schema accepted a broken daylight-factor grid"
    bad = copy.deepcopy(r)
    bad["targets"][1]["requirements"] = {"df_target_percent": 2.0}
    bad["targets"][1]["verdicts"] = {"df_target": grid["verdicts"]["df_target"]}
    bad["targets"][1]["verdict"] = "pass"
    assert errors(bad), "the schema accepted DF requirements on a surface"
