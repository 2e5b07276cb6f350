"""Provenance (docs/scene-format.md, "Provenance"): every results file names the scene content
and files it was traced from; `lightsolver verify`, `lightsolver.verify_results` and the
report's `provenance.check` refuse results that do not belong to a scene (another scene's, a
changed photometric file, no provenance) and accept the same scene re-indented; `lightsolver
check` lists a scene's errors and warnings without tracing."""
import hashlib
import json
import shutil
import subprocess

import jsonschema
import pytest

import lightsolver
import lightsolver_results
from conftest import SOURCE_DIR, without_run_facts

SCHEMA = json.loads((SOURCE_DIR / "docs" / "schemas" / "results.schema.json").read_text())
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA)
LAMPS = SOURCE_DIR / "Tests" / "golden" / "scenes" / "lamps.json"
OLD_RESULTS = {"format": "lightsolver.results/1", "photons": 1, "photons_requested": 1,
               "targets": []}


def run(cli, *args):
    return subprocess.run([cli, *map(str, args)], capture_output=True, text=True, timeout=120)


def traced(cli, scene, out, *extra):
    r = run(cli, "run", scene, "--photons", 20000, "--seed", 4, "--backend", "embree", "--quiet",
            "--out", out, *extra)
    assert r.returncode == 0, r.stderr
    return json.loads(out.read_text())


def canonical_sha256(doc) -> str:
    """The documented canonical form, written again here: keys sorted, no whitespace, integral
    numbers below 2^53 as integers."""
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


@pytest.fixture()
def lit_room(tmp_path, room_scene):
    """The room with a photometric downlight read from a file of its own folder."""
    doc = json.loads(room_scene.read_text())
    shutil.copy(SOURCE_DIR / "Resources" / "luminaires" / "downlight.ies", tmp_path / "down.ies")
    doc["luminaires"].append({"name": "down", "type": "photometric", "file": "down.ies",
                              "position": [3.0, 2.0, 2.9]})
    path = tmp_path / "room.json"
    path.write_text(json.dumps(doc, indent=1))
    return path


@pytest.fixture()
def lit_results(cli, lit_room, tmp_path):
    out = tmp_path / "results.json"
    return out, traced(cli, lit_room, out)


def test_every_results_file_names_its_scene_and_run(cli, lit_room, lit_results):
    _, res = lit_results
    assert list(VALIDATOR.iter_errors(res)) == []
    p = res["provenance"]
    assert p["scene_sha256"] == canonical_sha256(json.loads(lit_room.read_text()))
    ies = (lit_room.parent / "down.ies").read_bytes()
    assert p["files"] == [{"path": "down.ies", "kind": "photometric",
                           "sha256": hashlib.sha256(ies).hexdigest()}]
    assert p["solver_version"] == lightsolver.__version__
    assert p["backend"] == res["backend"] == "embree" and "Embree" in p["device"]
    assert p["mpi_ranks"] == 1 and p["threads"] >= 1
    assert p["options"]["photons"] == 20000 and p["options"]["seed"] == 4
    assert p["options"]["target_accuracy"] is None and "threads" not in p["options"]
    assert {o["name"] for o in lightsolver.run_options()} - {"threads", "backend"} \
        == set(p["options"])
    assert p["started_utc"] <= p["finished_utc"] and p["finished_utc"].endswith("Z")
    assert " run " in p["command"] and str(lit_room) in p["command"]


def test_thread_counts_and_python_agree_on_what_matters(cli, lit_room, tmp_path):
    one = traced(cli, lit_room, tmp_path / "one.json", "--threads", "1")
    three = traced(cli, lit_room, tmp_path / "three.json", "--threads", "3")
    assert (one["provenance"]["threads"], three["provenance"]["threads"]) == (1, 3)
    same = lambda r: without_run_facts(r, also=("threads",))["provenance"]  # noqa: E731
    assert same(one) == same(three)
    py = lightsolver.solve(lightsolver.load_scene(str(lit_room)), photons=20000, seed=4,
                           backend="embree", threads=1)
    assert py["provenance"]["command"].startswith("python: lightsolver.solve")
    assert same(py) == same(one)
    # Scene content given as a dict (JSON text): hashed the same way, files from base_dir.
    doc = json.loads(lit_room.read_text())
    text = lightsolver.scene_from_json(json.dumps(doc), str(lit_room.parent))
    assert same(lightsolver.solve(text, photons=20000, seed=4, backend="embree")) == same(one)


def test_a_scene_built_in_memory_has_no_hash(room_scene):
    scene = lightsolver.load_scene(str(room_scene))
    loaded = lightsolver.solve(scene, photons=10000)
    assert loaded["provenance"]["scene_sha256"] == canonical_sha256(
        json.loads(room_scene.read_text()))
    scene.add_light("extra", "point", position=[1, 1, 2], flux_lm=100)
    changed = lightsolver.solve(scene, photons=10000)
    assert changed["provenance"]["scene_sha256"] is None
    assert list(VALIDATOR.iter_errors(lightsolver_results.plain(changed))) == []
    problems = lightsolver.verify_results(str(room_scene), changed)
    assert len(problems) == 1 and "cannot be verified" in problems[0]


def test_verify_accepts_the_same_scene_reindented(cli, lit_room, lit_results):
    out, res = lit_results
    r = run(cli, "verify", lit_room, out)
    assert (r.returncode, r.stdout.strip()) == (0, f"{out}: results belong to {lit_room}")
    doc = json.loads(lit_room.read_text())
    lit_room.write_text(json.dumps(dict(reversed(list(doc.items()))), indent=7))
    assert run(cli, "verify", lit_room, out).returncode == 0
    assert lightsolver.verify_results(str(lit_room), res) == []


def test_verify_refuses_another_scenes_results(cli, room_scene, tmp_path):
    # The case: the room's report with the results of another scene.
    out = tmp_path / "lamps.json"
    res = traced(cli, LAMPS, out)
    r = run(cli, "verify", room_scene, out)
    assert r.returncode == 1
    lines = r.stdout.splitlines()
    assert lines[0] == f"{out}: results do not belong to {room_scene}:"
    assert "scene's content differs" in lines[1]
    assert any('"downlight_tilt.ies", which the scene does not read now' in x for x in lines)
    assert [x.strip() for x in lines[1:]] == lightsolver.verify_results(str(room_scene), res)


def test_verify_names_a_changed_photometric_file(cli, lit_room, lit_results):
    out, res = lit_results
    ies = lit_room.parent / "down.ies"
    ies.write_text(ies.read_text().replace("[MANUFAC]", "[MANUFAC] other", 1))
    r = run(cli, "verify", lit_room, out)
    assert r.returncode == 1
    assert r.stdout.splitlines()[1:] == \
        ['  photometric file "down.ies" changed since the results were traced']
    ies.unlink()
    assert lightsolver.verify_results(str(lit_room), res) == \
        ['photometric file "down.ies" is missing or cannot be read']


def test_verify_cannot_verify_results_without_provenance(cli, lit_room, lit_results, tmp_path):
    _, res = lit_results
    del res["provenance"]  # as a solver before issue 24 wrote them
    path = tmp_path / "old.json"
    path.write_text(json.dumps(res))
    r = run(cli, "verify", lit_room, path)
    assert r.returncode == 1 and "cannot be verified" in r.stdout
    # An optimizer's output is verified as one (test_optimize_provenance.py): not this scene's.
    optimized = SOURCE_DIR / "Tests" / "golden" / "cornell.results.json"
    r = run(cli, "verify", lit_room, optimized)
    assert r.returncode == 1 and "optimizer output does not belong" in r.stdout
    assert lightsolver_results.read(res).provenance is None
    truncated = tmp_path / "truncated.json"
    truncated.write_text(json.dumps(OLD_RESULTS)[:30])
    r = run(cli, "verify", lit_room, truncated)
    assert r.returncode == 1 and "error:" in r.stderr and str(truncated) in r.stderr


def test_reader_gives_the_provenance(lit_results):
    _, res = lit_results
    p = lightsolver_results.read(res).provenance
    assert p.scene_sha256 == res["provenance"]["scene_sha256"]
    assert [f.path for f in p.files] == ["down.ies"] and p.options["seed"] == 4


def test_report_check_refuses_what_does_not_belong(cli, room_scene, lit_room, lit_results,
                                                   tmp_path):
    from lightsolver_report import ReportError, provenance

    out, res = lit_results
    provenance.check(lit_room, res)
    provenance.check(lit_room, out)  # a results file
    provenance.check(lit_room, lightsolver_results.read(res))  # the reader's view
    with pytest.raises(ReportError, match="do not belong to the model room.json.*content "
                                          "differs.*down.ies"):
        provenance.check(room_scene, res)  # another scene's results
    ies = lit_room.parent / "down.ies"
    ies.write_bytes(ies.read_bytes() + b"\n")
    with pytest.raises(ReportError) as refused:
        provenance.check(lit_room, res)
    assert "photometric file \"down.ies\" changed" in str(refused.value)
    assert "content differs" not in str(refused.value)
    # Without provenance: refused unless the caller allows it, and a mismatch never is.
    with pytest.raises(ReportError, match="cannot be verified"):
        provenance.check(room_scene, OLD_RESULTS)
    provenance.check(room_scene, OLD_RESULTS, allow_unverified=True)
    with pytest.raises(ReportError, match="do not belong"):
        provenance.check(lit_room, res, allow_unverified=True)


def test_check_lists_every_error_and_warning(cli, room_scene, tmp_path):
    r = run(cli, "check", room_scene)
    assert r.returncode == 0 and r.stdout.strip().endswith("0 errors, 0 warnings")
    # A scene with warnings: every luminaire at zero flux (nothing to trace).
    scene = json.loads(room_scene.read_text())
    for lum in scene["luminaires"]:
        lum["flux_lm"] = 0
    for mesh in scene["meshes"]:
        if "file" in mesh:
            mesh["file"] = str((room_scene.parent / mesh["file"]).resolve())
    office = tmp_path / "dark.json"
    office.write_text(json.dumps(scene))
    r = run(cli, "check", office)
    found = lightsolver.check_scene_file(str(office))
    assert r.returncode == 0 and found["warnings"]
    for w in found["warnings"]:
        assert w["message"] in r.stdout
    assert r.stdout.count("\nwarning: ") + r.stdout.startswith("warning: ") \
        == len(found["warnings"])
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "lightsolver.scene/1", "materials": {}, "meshes": [],'
                   ' "luminaires": [{"name": "l", "type": "point", "flux_lm": -1,'
                   ' "position": [0, 0, 1]}], "targets": []}')
    r = run(cli, "check", bad)
    assert r.returncode == 1
    errors = [x for x in r.stdout.splitlines() if x.startswith("error: ")]
    assert len(errors) == len(lightsolver.check_scene_file(str(bad))["errors"]) == 2
    assert "luminaires[0].flux_lm" in errors[0] and "2 errors" in r.stdout
    missing = run(cli, "check", tmp_path / "nowhere.json")
    assert missing.returncode == 1 and "nowhere.json" in missing.stdout + missing.stderr


def test_rescaled_results_belong_to_the_traced_scene_with_their_factors_noted(cli, tmp_path):
    # The golden rescale: the lamps scene's trace with three groups at other fluxes.
    rescaled = SOURCE_DIR / "Tests" / "golden" / "lamps_rescaled.embree.results.json"
    r = run(cli, "verify", LAMPS, rescaled)
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.splitlines() == [
        f"{rescaled}: results belong to {LAMPS}",
        '  note: the same trace with other group fluxes: the scene\'s fluxes times the recorded '
        'factors (rescaled): "accent" x 0.5, "downlights" x 1.7, "sun" x 0']
    doc = json.loads(rescaled.read_text())
    assert lightsolver_results.read(doc).rescaled == {
        "accent": 0.5, "downlights": 1.7, "general": 1.0, "sun": 0.0}
    assert lightsolver.verify_document(str(LAMPS), doc)["notes"] == \
        [r.stdout.splitlines()[1][len("  note: "):]]
    # A flux record that is not the solver's: the spot as traced while its group is halved.
    doc["luminaires"][2]["dimming"] = 1.0
    edited = tmp_path / "edited.json"
    edited.write_text(json.dumps(doc))
    r = run(cli, "verify", LAMPS, edited)
    assert r.returncode == 1
    assert r.stdout.splitlines()[1:] == [
        '  luminaire "spot" is dimmed by 1 but its group "accent" by 0.5: the results\' flux '
        "record is not the solver's"]
    assert lightsolver.verify_results(str(LAMPS), doc) == [r.stdout.splitlines()[1].strip()]


def test_python_combine_records_its_traces_and_fluxes(lit_room, room_scene):
    sim = lightsolver.Simulation(str(lit_room), backend="embree", threads=1)
    groups = sim.groups
    assert [g["name"] for g in groups] == ["panel 1", "panel 2", "panel 3", "panel 4", "down"]
    traces = [sim.trace_group(g, 20000, 4) for g in range(len(groups))]
    combined = sim.combine(traces, [g["flux_lm"] for g in groups])
    # Group traces follow the scene's next_event (auto, the default) as the run does.
    run_ = sim.run(photons=20000, seed=4)
    # Every group traced with the run's seed and combined at its flux is the run, bit for bit.
    assert [t["mean_lux"] for t in combined["targets"]] == \
        [t["mean_lux"] for t in run_["targets"]]
    assert list(VALIDATOR.iter_errors(lightsolver_results.plain(combined))) == []
    p = combined["provenance"]
    assert p["command"].startswith("python: lightsolver.Simulation.combine")
    same = lambda r: without_run_facts(r, also=("threads",))["provenance"]  # noqa: E731
    assert same(combined) == same(run_)
    assert combined["rescaled"] == {g["name"]: 1.0 for g in groups}
    # Other fluxes: the panels at half, the downlight dark (no trace).
    fluxes = [0.5 * g["flux_lm"] for g in groups[:4]] + [0.0]
    dimmed = sim.combine(traces[:4] + [None], fluxes)
    assert dimmed["rescaled"] == {**{g["name"]: 0.5 for g in groups[:4]}, "down": 0.0}
    assert lightsolver_results.read(dimmed).rescaled == dimmed["rescaled"]
    found = lightsolver.verify_document(str(lit_room), dimmed)
    assert found["differences"] == [] and '"down" x 0' in found["notes"][0]
    assert '"panel 1" x 0.5' in found["notes"][0]
    refused = lightsolver.verify_results(str(room_scene), dimmed)
    assert any("content differs" in d for d in refused)
