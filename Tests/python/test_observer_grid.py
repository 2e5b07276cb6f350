"""Observer grids (docs/glare.md, "Observer grids"): the CLI's results and ``solve()`` of a scene
whose grid came through ``Scene.add_target`` agree field by field and follow the results
schema; the maximum and its place are those of the points."""
import copy
import json

import lightsolver
from conftest import without_run_facts
from test_results_schema import TIMINGS, cli_results, errors, plain

EYES = {"corner": [0.5, 0.5, 1.2], "edge1": [5.0, 0, 0], "edge2": [0, 3.0, 0], "cells": [2, 2],
        "view_step_deg": 90, "task": "office-writing"}


def test_add_target_gives_the_scene_files_observer_grid(cli, room_scene, tmp_path):
    scene = json.loads(room_scene.read_text())
    scene["targets"].append({"name": "eyes", "type": "observer_grid", **EYES})
    path = tmp_path / "eyes.json"
    path.write_text(json.dumps(scene))
    from_cli = cli_results(cli, path, tmp_path, "--photons", "200000", "--seed", "3",
                           "--backend", "embree")
    built = lightsolver.load_scene(str(room_scene))
    built.add_target("eyes", "observer_grid", **EYES)
    from_py = plain(lightsolver.solve(built, photons=200000, seed=3, backend="embree"))
    assert errors(from_cli) == []
    assert errors(from_py) == []
    for doc in (from_cli, from_py):
        for key in TIMINGS:
            doc.pop(key)
        for target in doc["targets"]:  # an undecided verdict's seconds are a timing too
            for verdict in target.get("verdicts", {}).values():
                verdict.get("to_decide", {}).pop("seconds", None)
    # The Python scene was changed in memory (add_target): it has no file content to name.
    assert from_py["provenance"]["scene_sha256"] is None and from_py["provenance"]["files"] == []
    identity = ("scene_sha256", "files")  # the file's task reads the requirements table
    assert without_run_facts(from_py, also=identity) == without_run_facts(from_cli, also=identity)

    eyes = from_cli["targets"][-1]
    grid = eyes["observer_grid"]
    assert eyes["type"] == "observer_grid" and eyes["requirements"]["ugr_max"] == 19
    assert len(grid["positions"]) == 4 and len(grid["view_directions"]) == 4
    assert [len(row) for row in grid["ugr"]] == [4, 4, 4, 4]
    values = [u for row in grid["ugr"] for u in row if u is not None]
    assert values, "the room's panels give glare somewhere"
    at = grid["max_at"]
    assert eyes["ugr"] == max(values) == grid["ugr"][at["position"]][at["direction"]]
    assert eyes["ugr_ci_low"] <= eyes["ugr"] <= eyes["ugr_ci_high"]
    # Simultaneous: no narrower below than the arg-max point's own interval.
    assert eyes["ugr_ci_low"] <= grid["ugr_ci_low"][at["position"]][at["direction"]]
    assert eyes["verdicts"]["ugr"]["relation"] == "<="

    for mutate in [lambda t: t.pop("observer_grid"),
                   lambda t: t.update(type="observer"),
                   lambda t: t["observer_grid"].pop("max_at"),
                   lambda t: t["observer_grid"]["positions"].append([1, 2])]:
        bad = copy.deepcopy(from_cli)
        mutate(bad["targets"][-1])
        assert errors(bad), "the schema accepted a broken observer grid"


def test_add_target_refuses_a_bad_observer_grid(room_scene):
    built = lightsolver.load_scene(str(room_scene))
    keys = dict(EYES, view_step_deg=7)
    try:
        built.add_target("eyes", "observer_grid", **keys)
        lightsolver.solve(built, photons=1000, seed=1)
    except lightsolver.InputError as e:
        assert "view_step_deg" in str(e) and "divide 360" in str(e)
    else:
        raise AssertionError("a step of 7 degrees was accepted")
