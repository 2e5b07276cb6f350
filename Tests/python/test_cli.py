"""The command-line program: help, version, the table, results JSON, errors, Ctrl-C."""
import json
import signal
import subprocess
import time

import lightsolver


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
    r = run(cli, "run", str(bad), "--confidence", "2")
    assert r.returncode != 0


def test_ctrl_c_stops_cleanly_with_partial_results(cli, room_scene, tmp_path):
    out = tmp_path / "partial.json"
    p = subprocess.Popen([cli, "run", str(room_scene), "--photons", "5000000000", "--out", str(out)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.5)
    p.send_signal(signal.SIGINT)
    stdout, _ = p.communicate(timeout=60)
    assert p.returncode == 130
    assert "PARTIAL" in stdout
    res = json.loads(out.read_text())
    assert res["partial"] and 0 < res["photons"] < 5_000_000_000
    assert res["targets"][0]["mean_lux"] > 0


def test_cost_shows_accuracy_against_time(cli, room_scene):
    r = run(cli, "cost", str(room_scene), "--max-photons", "160000")
    assert r.returncode == 0, r.stderr
    rows = [line.split() for line in r.stdout.splitlines() if line.strip()[:1].isdigit()]
    assert [int(row[0]) for row in rows] == [10_000, 40_000, 160_000]
    widths = [float(row[2]) for row in rows]
    # 4x the photons halves the interval (within Monte Carlo noise).
    assert 1.6 < widths[0] / widths[1] < 2.5 and 1.6 < widths[1] / widths[2] < 2.5
    assert "±" in r.stdout and "photons" in r.stdout


def test_run_to_an_accuracy_goal(cli, room_scene, tmp_path):
    out = tmp_path / "acc.json"
    r = run(cli, "run", str(room_scene), "--accuracy", "0.05", "--photons", "100000000",
            "--out", str(out))
    assert r.returncode == 0, r.stderr
    res = json.loads(out.read_text())
    assert res["accuracy_met"] and res["target_accuracy"] == 0.05
    assert res["photons"] < 100_000_000 and not res["partial"]
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
