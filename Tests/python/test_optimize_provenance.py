"""The optimizer's output carries provenance (docs/optimization.md, "Provenance and
configurations"): the base scene's hash and files, the build, backend, device, processes and
threads, the resolved search settings, the block's hash and the domain; valid against
docs/schemas/optimization.schema.json; the same for every thread count and for Python but for
its run facts; `lightsolver verify` and `lightsolver.verify_results` accept it for its scene and
refuse it for another scene or another block; and where results are expected it is refused
with a message that says what it is."""
import copy
import hashlib
import json
import shutil
import subprocess

import jsonschema
import pytest

import lightsolver
import lightsolver_results
from conftest import SOURCE_DIR, without_run_facts

SCHEMAS = SOURCE_DIR / "docs" / "schemas"
SMALL_ROOM = SOURCE_DIR / "Examples" / "optimization" / "small_room" / "small_room.json"
#: A short search: a few iterations at small photon counts.
SHORT = ("--iterations", "3", "--screening-photons", "2048", "--confirmation-photons", "16384")
#: Differ between two searches of the same scene and options: the clock's and the machine's.
TIMINGS = ("update_seconds", "trace_seconds", "other_seconds", "total_seconds")


def validator() -> jsonschema.Draft202012Validator:
    """The optimization schema, its reference to the results' provenance fields resolved (by
    the `referencing` registry where jsonschema has one, else its RefResolver: Debian 12)."""
    load = lambda name: json.loads((SCHEMAS / name).read_text())  # noqa: E731
    schema, results = load("optimization.schema.json"), load("results.schema.json")
    try:
        from referencing import Registry, Resource
    except ImportError:
        resolver = jsonschema.RefResolver("", schema, store={"results.schema.json": results})
        return jsonschema.Draft202012Validator(schema, resolver=resolver)
    registry = Registry().with_resource("results.schema.json", Resource.from_contents(results))
    return jsonschema.Draft202012Validator(schema, registry=registry)


def canonical_sha256(doc) -> str:
    """The documented canonical form (docs/scene-format.md, "Provenance"), written again."""
    def norm(x):
        if isinstance(x, dict):
            return {k: norm(v) for k, v in x.items()}
        if isinstance(x, list):
            return [norm(v) for v in x]
        if isinstance(x, float) and x.is_integer() and abs(x) < 2 ** 53:
            return int(x)
        return x
    text = json.dumps(norm(doc), sort_keys=True, separators=(",", ":"), ensure_ascii=False)
    return hashlib.sha256(text.encode()).hexdigest()


def run(cli, *args):
    return subprocess.run([cli, *map(str, args)], capture_output=True, text=True, timeout=300)


def optimize(cli, scene, out, *extra) -> dict:
    r = run(cli, "optimize", scene, "-q", *SHORT, "--out", out, *extra)
    assert r.returncode == 0, r.stderr
    return json.loads(out.read_text())


def comparable(doc: dict, also=()) -> dict:
    """The output without timings and the provenance's run facts (and `also`)."""
    def strip(x):
        if isinstance(x, dict):
            return {k: strip(v) for k, v in x.items() if k not in TIMINGS}
        return [strip(v) for v in x] if isinstance(x, list) else x
    return strip(without_run_facts(doc, also=also))


@pytest.fixture()
def room(tmp_path):
    """The small room example in a folder of its own (its block may be edited)."""
    path = tmp_path / "small_room.json"
    shutil.copy(SMALL_ROOM, path)
    return path


@pytest.fixture()
def searched(cli, room, tmp_path):
    out = tmp_path / "opt.json"
    return out, optimize(cli, room, out, "--threads", "1")


def test_output_names_its_scene_search_and_domain(room, searched):
    _, doc = searched
    assert [e.message for e in validator().iter_errors(doc)] == []
    p = doc["provenance"]
    scene = json.loads(room.read_text())
    assert p["scene_sha256"] == canonical_sha256(scene) and p["files"] == []
    assert p["optimization_sha256"] == canonical_sha256(scene["optimization"])
    assert p["solver_version"] == lightsolver.__version__
    assert p["backend"] == "embree" and "Embree" in p["device"]
    assert (p["mpi_ranks"], p["threads"]) == (1, 1)
    o = p["options"]
    assert (o["max_iterations"], o["screening_photons"], o["confirmation_photons"]) \
        == (3, 2048, 16384)
    assert (o["seed"], o["confidence"], o["strategy"], o["reuse_traces"]) \
        == (1, 0.95, "confirm", True)
    assert p["started_utc"] <= p["finished_utc"]
    assert " optimize " in p["command"] and str(room) in p["command"]
    # The domain maps every member's cells to its values.
    domain = p["domain"]
    assert [d["name"] for d in domain] == doc["variables"]
    assert doc["isoc"], "the short search found no configuration"
    for member in doc["isoc"]:
        for d, cell, value in zip(domain, member["cells"], member["values"]):
            expected = d["levels"][cell] if "levels" in d else \
                d["min"] + (cell + 0.5) * (d["max"] - d["min"]) / d["cells"]
            assert value == pytest.approx(expected, rel=1e-12, abs=1e-12)


def test_thread_counts_and_python_agree_on_what_matters(cli, room, searched, tmp_path):
    _, one = searched
    two = optimize(cli, room, tmp_path / "two.json", "--threads", "2")
    assert two["provenance"]["threads"] == 2
    assert comparable(two, also=("threads",)) == comparable(one, also=("threads",))
    py = lightsolver.optimize(str(room), iterations=3, screening_photons=2048,
                              confirmation_photons=16384, threads=1, backend="embree")
    assert py["provenance"]["command"].startswith("python: lightsolver.optimize")
    assert comparable(py) == comparable(one)


def test_verify_accepts_its_scene_and_refuses_another_block_or_scene(cli, room, searched,
                                                                      room_scene):
    out, doc = searched
    r = run(cli, "verify", room, out)
    assert r.returncode == 0, r.stdout + r.stderr
    lines = r.stdout.splitlines()
    assert lines[0] == f"{out}: optimizer output belongs to {room}"
    assert "not results" in lines[1]
    assert lightsolver.verify_results(str(room), doc) == []
    found = lightsolver.verify_document(str(room), doc)
    assert found["optimization"] and found["differences"] == [] and found["notes"]
    # Another block given in the file's place (Python): the scene file is the same, the block not.
    block = copy.deepcopy(json.loads(room.read_text())["optimization"])
    block["search"]["seed"] = 2
    other = lightsolver.optimize(str(room), optimization=block, iterations=1,
                                 screening_photons=1024, confirmation_photons=4096)
    assert [e.message for e in validator().iter_errors(other)] == []
    assert lightsolver.verify_results(str(room), other) == [
        "the optimization block searched differs from the scene's (changed since, or given in "
        "its place)"]
    # The block edited in the file since the search: the content and the block differ.
    scene = json.loads(room.read_text())
    scene["optimization"] = block
    room.write_text(json.dumps(scene, indent=2))
    r = run(cli, "verify", room, out)
    assert r.returncode == 1
    assert r.stdout.splitlines()[0] == f"{out}: optimizer output does not belong to {room}:"
    assert "content differs" in r.stdout and "optimization block searched differs" in r.stdout
    # Another scene, and an output without provenance.
    r = run(cli, "verify", room_scene, out)
    assert r.returncode == 1 and "content differs" in r.stdout
    del doc["provenance"]
    assert "cannot be verified" in lightsolver.verify_results(str(room), doc)[0]


def test_the_golden_outputs_follow_the_schema():
    for name in ("cornell", "hangar", "conference"):
        doc = json.loads((SOURCE_DIR / "Tests" / "golden" / f"{name}.results.json").read_text())
        assert [e.message for e in validator().iter_errors(doc)] == [], name
        assert doc["provenance"]["options"]["reuse_traces"] is True, name


def test_where_results_are_expected_it_is_refused_clearly(cli, searched, tmp_path):
    out, _ = searched
    r = run(cli, "rescale", out, "--dim", "a=1", "--out", tmp_path / "x.json")
    assert r.returncode != 0 and "an optimizer's output" in r.stderr and "not results" in r.stderr
    assert not (tmp_path / "x.json").exists()
    with pytest.raises(lightsolver_results.ResultsError, match="an optimizer's output"):
        lightsolver_results.read(out)
    p = lightsolver_results.read_provenance(json.loads(out.read_text()))
    assert p.optimization_sha256 and [d["name"] for d in p.domain][:2] == ["a.u", "a.v"]
