"""The command-line program: help, version, the table, results JSON, errors, Ctrl-C, output
paths checked before tracing and written atomically, time limits and accuracy budgets."""
import json
import os
import signal
import subprocess
import time

import lightsolver
import pytest

from conftest import without_run_facts


def run(cli, *args, **kw):
    return subprocess.run([cli, *args], capture_output=True, text=True, timeout=120, **kw)


def test_help_and_version(cli):
    r = run(cli, "--help")
    assert r.returncode == 0 and "run" in r.stdout
    r = run(cli, "run", "--help")
    assert r.returncode == 0 and "--photons" in r.stdout and "--confidence" in r.stdout
    r = run(cli, "--version")
    assert r.returncode == 0 and r.stdout.strip() == f"lightsolver {lightsolver.__version__}"
    assert run(cli).returncode != 0  # no subcommand: usage error


def test_run_prints_table_and_writes_results(cli, room_scene, tmp_path):
    out = tmp_path / "results.json"
    r = run(cli, "run", str(room_scene), "--photons", "200000", "--seed", "5", "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert "workplane" in r.stdout and "U0" in r.stdout and "200000 photons" in r.stdout
    res = json.loads(out.read_text())
    assert res["format"] == "lightsolver.results/1"
    assert res["photons"] == 200_000 and res["backend"] == "embree" and not res["partial"]
    grid = next(t for t in res["targets"] if t["type"] == "grid")
    nu, nv = grid["cells_uv"]
    assert len(grid["cells"]) == nu * nv
    assert {"lux", "ci_low_lux", "ci_high_lux"} <= set(grid["cells"][0])
    assert grid["uniformity"] == grid["min_lux"] / grid["mean_lux"]
    # The Python module gives the same numbers for the same seed.
    py = lightsolver.solve(lightsolver.load_scene(str(room_scene)), photons=200_000, seed=5)
    for a, b in zip(res["targets"], py["targets"]):
        assert a["mean_lux"] == b["mean_lux"] and a["hits"] == b["hits"]


def test_errors_name_the_file_and_field(cli, tmp_path):
    bad = tmp_path / "broken.json"
    bad.write_text('{"format": "lightsolver.scene/1", "materials": {}, "meshes": [],'
                   ' "luminaires": [{"name": "l", "type": "point", "flux_lm": -1,'
                   ' "position": [0,0,0]}], "targets": []}')
    r = run(cli, "run", str(bad))
    assert r.returncode == 1
    assert "broken.json: luminaires[0].flux_lm: must be a finite value >= 0" in r.stderr
    r = run(cli, "run", str(tmp_path / "missing.json"))
    assert r.returncode != 0 and "missing.json" in r.stderr



def test_a_bad_confidence_is_named(cli, room_scene):
    # A valid scene, so the option is the only thing wrong.
    r = run(cli, "run", str(room_scene), "--photons", "1000", "--confidence", "2")
    assert r.returncode != 0 and "--confidence" in r.stderr, r.stderr
    assert "photons" not in r.stdout  # nothing traced


def test_ctrl_c_stops_cleanly_with_partial_results(cli, room_scene, tmp_path):
    out = tmp_path / "partial.json"
    # next_event "on": at 5e9 photons `auto` would leave every target's direct light to the
    # photons (docs/statistics.md, "When shadow rays pay"); this checks a cancel with shadow rays.
    p = subprocess.Popen([cli, "run", str(room_scene), "--photons", "5000000000", "--next-event",
                          "on", "--out", str(out)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.5)
    p.send_signal(signal.SIGINT)
    stdout, _ = p.communicate(timeout=60)
    assert p.returncode == 130
    assert "PARTIAL" in stdout
    res = json.loads(out.read_text())
    assert res["partial"] and 0 < res["photons"] < 5_000_000_000
    assert res["stop_reason"] == "cancelled"
    assert res["targets"][0]["mean_lux"] > 0
    # Next-event estimation: the default points' direct parts, traced before the
    # photons, are whole; the finer ones planned for 5e9 photons were not traced.
    assert "next_event_direct" in res["effects"]["simulated"]
    assert any("direct light was sampled as planned" in w for w in res["warnings"])


def cost_rows(stdout):
    return [line.split() for line in stdout.splitlines() if line.strip()[:1].isdigit()]


def test_cost_shows_accuracy_against_time(cli, room_scene):
    r = run(cli, "cost", str(room_scene), "--max-photons", "160000")
    assert r.returncode == 0, r.stderr
    rows = cost_rows(r.stdout)
    assert [int(row[0]) for row in rows] == [10_000, 40_000, 160_000]
    widths = [float(row[2]) for row in rows]
    # 4x the photons halves the interval (within Monte Carlo noise).
    assert 1.6 < widths[0] / widths[1] < 2.5 and 1.6 < widths[1] / widths[2] < 2.5
    # One run: a row's tracing time includes the rows before it.
    seconds = [float(row[1]) for row in rows]
    assert seconds == sorted(seconds) and "one run of embree" in r.stdout
    # Each goal's photons come from the last row by width ~ 1/sqrt(N).
    goals = {line.split("%")[0].strip(" ±"): float(line.split(":")[1].split()[0])
             for line in r.stdout.splitlines() if line.strip().startswith("±")}
    assert set(goals) == {"10.0", "5.0", "2.0", "1.0", "0.5"}
    assert goals["1.0"] == pytest.approx(160_000 * (widths[2] / 1.0) ** 2, rel=0.015)
    assert goals["0.5"] / goals["1.0"] == pytest.approx(4.0, rel=1e-2)


#: Every backend of this build that can start here (Vulkan on lavapipe in CI).
TRACING_BACKENDS = [b["name"] for b in lightsolver.backends()
                    if b["name"] != "auto" and b["available"]]


@pytest.mark.parametrize("backend", TRACING_BACKENDS)
def test_cost_rows_are_checkpoints_of_one_run(cli, room_scene, tmp_path, backend):
    """The table's photons are the first photons of one run, none traced twice: the run ends at
    the last row with exactly the numbers of a plain run of that many photons and seed."""
    cost_out, run_out = tmp_path / "cost.json", tmp_path / "run.json"
    c = run(cli, "cost", str(room_scene), "--max-photons", "200000", "--seed", "11",
            "--backend", backend, "--out", str(cost_out))
    assert c.returncode == 0, c.stderr
    rows = cost_rows(c.stdout)
    assert [int(row[0]) for row in rows] == [10_000, 40_000, 160_000]
    r = run(cli, "run", str(room_scene), "--photons", "160000", "--seed", "11",
            "--backend", backend, "--out", str(run_out), "--quiet")
    assert r.returncode == 0, r.stderr
    a, b = json.loads(cost_out.read_text()), json.loads(run_out.read_text())
    assert a["photons"] == a["photons_requested"] == 160_000  # traced once, to the last row
    for doc in (a, b):
        doc.pop("seconds")
    # bit for bit: every estimate, cell, tally count and warning; the same scene and options
    assert without_run_facts(a) == without_run_facts(b)
    # Every row's width is the worst target (whole grids) of a plain run of its photons.
    for row in rows:
        r = run(cli, "run", str(room_scene), "--photons", row[0], "--seed", "11",
                "--backend", backend, "--out", str(run_out), "--quiet")
        worst = worst_relative_half_width(json.loads(run_out.read_text()))
        assert float(row[2]) == pytest.approx(100 * worst, abs=5e-4)  # printed to 0.001 %


def worst_relative_half_width(results):
    return max((t["ci_high_lux"] - t["ci_low_lux"]) / 2 / t["mean_lux"]
               for t in results["targets"])


def layout_only(results):
    """The JSON layout of a results dict: no timing, no numpy arrays beside it."""
    results = dict(results, targets=[{k: v for k, v in t.items() if not k.startswith("cells_")}
                                     for t in results["targets"]])
    results.pop("seconds")
    return without_run_facts(results)  # provenance: not when or how it was started


def test_python_cost_is_one_run_whose_checkpoints_are_its_first_photons(room_scene):
    scene = lightsolver.load_scene(str(room_scene))
    c = lightsolver.cost(scene, max_photons=160_000, seed=7)
    rows = c["rows"]
    assert [row["photons"] for row in rows] == [10_000, 40_000, 160_000]
    assert c["results"]["photons"] == c["results"]["photons_requested"] == 160_000
    assert [row["seconds"] for row in rows] == sorted(row["seconds"] for row in rows)
    # Each row is what a plain run of its photon count gives (photon i is photon i) ...
    for row in rows:
        plain = lightsolver.solve(scene, photons=row["photons"], seed=7)
        assert row["worst_relative_half_width"] == pytest.approx(
            worst_relative_half_width(plain), rel=1e-12)
    # ... and the run ends with exactly the last one's results.
    assert layout_only(c["results"]) == layout_only(plain)
    # The goals come from the last row by the solver's one rule (accuracy_cost).
    last = rows[-1]
    assert [g["accuracy"] for g in c["goals"]] == [0.10, 0.05, 0.02, 0.01, 0.005]
    for g in c["goals"]:
        need = last["photons"] * (last["worst_relative_half_width"] / g["accuracy"]) ** 2
        assert g["photons"] == pytest.approx(need, rel=1e-12)
        assert g["seconds"] == pytest.approx(need * last["seconds"] / last["photons"], rel=1e-12)
    with pytest.raises(lightsolver.InputError, match="max_photons"):
        lightsolver.cost(scene, max_photons=9_999)


def test_cost_refuses_a_run_without_rows(cli, room_scene):
    r = run(cli, "cost", str(room_scene), "--max-photons", "5000")
    assert r.returncode == 1 and "--max-photons" in r.stderr


def test_run_to_an_accuracy_goal(cli, room_scene, tmp_path):
    out = tmp_path / "acc.json"
    r = run(cli, "run", str(room_scene), "--accuracy", "0.05", "--photons", "100000000",
            "--out", str(out))
    assert r.returncode == 0, r.stderr
    res = json.loads(out.read_text())
    assert res["accuracy_met"] and res["target_accuracy"] == 0.05
    assert res["photons"] < 100_000_000 and not res["partial"]
    assert res["stop_reason"] == "accuracy"
    for t in res["targets"]:
        assert (t["ci_high_lux"] - t["ci_low_lux"]) / 2 <= 0.05 * t["mean_lux"]


def test_photometry_summary_and_plot(cli, tmp_path):
    from conftest import SOURCE_DIR
    png = tmp_path / "polar.png"
    r = run(cli, "photometry", str(SOURCE_DIR / "Resources/luminaires/wallwasher.ies"),
            "--plot", str(png))
    assert r.returncode == 0, r.stderr
    assert "Peak" in r.stdout and "Beam angle" in r.stdout and "Lumens (integrated)" in r.stdout
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    bad = tmp_path / "bad.ies"
    bad.write_text("IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 3\n")
    r = run(cli, "photometry", str(bad))
    assert r.returncode == 1 and "bad.ies" in r.stderr and "line" in r.stderr


# A run of days: if an output path were only checked after tracing, these tests would time out.
DAYS = "10000000000000"


def run_fast(cli, *args):
    """A command that must fail at once; returns (result, seconds)."""
    start = time.monotonic()
    r = subprocess.run([cli, *args], capture_output=True, text=True, timeout=30)
    return r, time.monotonic() - start


def test_unwritable_out_fails_before_tracing(cli, room_scene, tmp_path):
    # Root ignores permission bits, so unwritable paths are made otherwise: a missing folder, a
    # folder as the target, a regular file used as a folder, and /proc (no new files there).
    (tmp_path / "folder").mkdir()
    (tmp_path / "plain").write_text("keep")
    cases = {tmp_path / "missing" / "r.json": "does not exist",
             tmp_path / "folder": "it is a folder",
             tmp_path / "plain" / "r.json": "is not a folder",
             "/proc/lightsolver-test.json": "cannot create files in '/proc'"}
    for out, why in cases.items():
        r, seconds = run_fast(cli, "run", str(room_scene), "--photons", DAYS, "--out", str(out))
        assert r.returncode == 1, (out, r.stderr)
        assert f"error: cannot write the results file '{out}'" in r.stderr and why in r.stderr
        assert seconds < 20 and r.stdout == ""  # nothing traced
    assert sorted(os.listdir(tmp_path)) == ["folder", "plain"]  # nothing created
    assert os.listdir(tmp_path / "folder") == [] and (tmp_path / "plain").read_text() == "keep"
    assert not os.path.exists("/proc/lightsolver-test.json")


def test_an_existing_file_survives_a_failed_write(cli, room_scene):
    # /proc/version exists and can be read, but nothing can be created next to it: the write
    # is refused before tracing and the file is untouched.
    before = open("/proc/version").read()
    r, _ = run_fast(cli, "run", str(room_scene), "--photons", DAYS, "--out", "/proc/version")
    assert r.returncode == 1 and "'/proc/version'" in r.stderr
    assert open("/proc/version").read() == before


def test_results_are_replaced_atomically(cli, room_scene, tmp_path):
    out = tmp_path / "r.json"
    out.write_text("previous results")
    os.symlink(out, tmp_path / "link.json")
    for seed in ("1", "2"):
        r = run(cli, "run", str(room_scene), "--photons", "20000", "--seed", seed, "-q",
                "--out", str(tmp_path / "link.json"))
        assert r.returncode == 0, r.stderr
        assert json.loads(out.read_text())["seed"] == int(seed)
    assert sorted(os.listdir(tmp_path)) == ["link.json", "r.json"]  # no temporary file left
    assert os.path.islink(tmp_path / "link.json")


def test_optimize_and_plot_outputs_are_checked_first(cli, tmp_path):
    from conftest import SOURCE_DIR
    room = SOURCE_DIR / "Examples" / "optimization" / "small_room" / "small_room.json"
    r, _ = run_fast(cli, "optimize", str(room), "--iterations", "100000",
                    "--out", str(tmp_path / "missing" / "isoc.json"))
    assert r.returncode == 1 and "cannot write the results file" in r.stderr, r.stderr
    assert r.stdout == ""  # no iteration was searched
    ies = SOURCE_DIR / "Resources/luminaires/wallwasher.ies"
    r, _ = run_fast(cli, "photometry", str(ies), "--plot", str(tmp_path))
    assert r.returncode == 1 and "cannot write the plot" in r.stderr and r.stdout == ""
    png = tmp_path / "polar.png"
    for _ in range(2):
        r, _ = run_fast(cli, "photometry", str(ies), "--plot", str(png))
        assert r.returncode == 0, r.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert os.listdir(tmp_path) == ["polar.png"]


def test_time_limit_ends_a_long_run_with_an_estimate(cli, room_scene, tmp_path):
    out = tmp_path / "r.json"
    r, seconds = run_fast(cli, "run", str(room_scene), "--photons", DAYS, "--max-seconds", "1.5",
                          "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert seconds < 20
    # Printed once the first batches give a rate, because the run would last over a minute.
    assert "tracing 1e+13 photons, about " in r.stderr and " photons/s" in r.stderr
    assert "the time limit (1.5 s) will end it first" in r.stderr
    assert "stopped: time limit 1.5 s" in r.stdout and "PARTIAL" not in r.stdout
    res = json.loads(out.read_text())
    assert res["stop_reason"] == "time" and res["max_seconds"] == 1.5 and not res["partial"]
    assert 0 < res["photons"] < int(DAYS) and res["photons_requested"] == int(DAYS)
    assert any("machine's speed" in w for w in res["warnings"])
    r = run(cli, "run", str(room_scene), "--photons", "20000", "-q")
    assert r.returncode == 0 and r.stderr == ""  # short runs print no estimate
    r = run(cli, "run", str(room_scene), "--max-seconds", "0")
    assert r.returncode != 0 and "--max-seconds" in r.stderr


def test_accuracy_without_photons_is_not_capped_by_the_scene(cli, room_scene, tmp_path):
    doc = json.loads(room_scene.read_text())
    doc["settings"]["photons"] = 10_000  # far too few for +-2 %
    scene = tmp_path / "room.json"
    scene.write_text(json.dumps(doc))
    out = tmp_path / "r.json"
    r = run(cli, "run", str(scene), "--accuracy", "0.02", "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert "stopped: accuracy goal ±2 % met" in r.stdout
    res = json.loads(out.read_text())
    assert res["stop_reason"] == "accuracy" and res["accuracy_met"]
    assert res["photons"] > 10_000 and res["photons_requested"] == 10_000_000_000
    assert res["max_seconds"] == 300 and not res["warnings"]
    for t in res["targets"]:
        assert (t["ci_high_lux"] - t["ci_low_lux"]) / 2 <= 0.02 * t["mean_lux"]
    # An explicit photon count stays the budget: the goal is then missed, with a warning.
    r = run(cli, "run", str(scene), "--accuracy", "0.02", "--photons", "10000", "--out", str(out))
    res = json.loads(out.read_text())
    assert r.returncode == 0 and res["stop_reason"] == "photons" and not res["accuracy_met"]
    assert "max_seconds" not in res and res["warnings"]


def test_backend_choices_and_help_come_from_the_registry(cli, room_scene):
    names = [b["name"] for b in lightsolver.backends()]
    for command in ("run", "cost"):
        r = run(cli, command, "--help")
        assert r.returncode == 0
        help_text = " ".join(r.stdout.split())  # CLI11 may wrap long descriptions
        for b in lightsolver.backends():
            assert f"{b['name']} ({' '.join(b['description'].split())})" in help_text, help_text
    r = run(cli, "run", str(room_scene), "--photons", "1000", "--backend", "cuda")
    assert r.returncode != 0
    assert "cuda" in r.stderr and all(name in r.stderr for name in names), r.stderr


def test_backends_command_lists_the_registry_with_availability(cli):
    r = run(cli, "backends")
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    listed = lightsolver.backends()
    assert [line.split()[0] for line in lines] == [b["name"] for b in listed]
    for line, b in zip(lines, listed):
        assert ("not available" in line) == (not b["available"]), line
        assert (line.split()[1] == "GPU") == b["gpu"], line
