"""One results contract: the CLI's results file and ``lightsolver.solve()`` both follow
docs/schemas/results.schema.json and agree field by field for the same scene and seed."""
import copy
import json
import subprocess

import jsonschema
import pytest

import lightsolver
from conftest import SOURCE_DIR

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
    assert from_py == from_cli  # every number to the bit, every key, every warning


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
