"""A year of daylight (`lightsolver annual`, lightsolver.annual; docs/daylight.md, "A year of
daylight"): the files the command writes, read back; the metrics' sanity on grids whose answer is
known (open to the sky everywhere; fully shaded); an sDA interval that covers the value of a 16x
longer trace; bad input named, nothing written."""
import hashlib
import json
import math
import subprocess

import lightsolver
import numpy as np
import pytest

from conftest import SOURCE_DIR

CHICAGO = SOURCE_DIR / "Tests/native/sun/data/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw"
ROOM = SOURCE_DIR / "Examples/daylight/annual_side_lit_room.scene.json"


def cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(lightsolver_cli()), *args], capture_output=True, text=True)


def lightsolver_cli():
    import os
    return os.environ["LIGHTSOLVER_CLI"]


def open_site_scene(tmp_path, grid_normal_up=True, ground=0.2):
    """No geometry: a 2 x 2 grid at the centre of a site disc, facing up (or down)."""
    e2 = [0, 1, 0] if grid_normal_up else [0, -1, 0]
    corner = [-0.5, -0.5, 0] if grid_normal_up else [-0.5, 0.5, 0]
    scene = {"format": "lightsolver.scene/1", "materials": {}, "meshes": [],
             "luminaires": [{"name": "sky", "type": "sky", "model": "uniform",
                             "zenith_luminance_cd_m2": 1000, "ground_reflectance": ground,
                             "site": {"centre": [0, 0, 0], "radius_m": 1.0}}],
             "targets": [{"name": "open", "type": "grid", "corner": corner, "edge1": [1, 0, 0],
                          "edge2": e2, "cells": [2, 2]}]}
    path = tmp_path / "open.scene.json"
    path.write_text(json.dumps(scene))
    return path


def test_cli_writes_the_metrics_and_every_hour(tmp_path):
    out = tmp_path / "out"
    r = cli("annual", str(ROOM), "--weather", str(CHICAGO), "--photons", "2000000",
            "--out-dir", str(out))
    assert r.returncode == 0, r.stderr
    assert "sDA300/50%" in r.stdout
    summary = json.loads((out / "annual.json").read_text())
    assert summary["format"] == "lightsolver.annual/1"
    assert summary["weather"]["sha256"] == hashlib.sha256(CHICAGO.read_bytes()).hexdigest()
    assert summary["weather"]["hours"] == 8760 and summary["weather"]["sky_hours"] == 4414
    assert summary["occupancy"]["hours"] == 3650 and summary["daylight_hours"] == 4380
    assert summary["trace"]["photons"] == 2000000 and summary["sky"]["patches"] == 146
    grid = summary["grids"][0]
    assert grid["cells"] == 300 and grid["name"] == "work plane"
    m = grid["metrics"]
    for key in ("sda_percent", "da_fraction", "udi_useful_fraction"):
        assert m[key]["low"] <= m[key]["estimate"] <= m[key]["high"]
    arrays = np.load(out / "annual.npz")
    for name in ("g0_mean", "g0_low", "g0_high", "g0_direct_sun"):
        assert arrays[name].shape == (8760, 300) and arrays[name].dtype == np.float32
    assert np.all(arrays["g0_low"] <= arrays["g0_mean"])
    assert np.all(arrays["g0_mean"] <= arrays["g0_high"])
    assert np.all(np.isfinite(arrays["g0_high"]))
    assert arrays["month_day_hour"].shape == (8760, 3)
    assert (out / "annual.npz").stat().st_size < 0.8 * 4 * 8760 * 300 * 4  # deflated


def test_open_grid_has_full_sda_and_the_ase_its_sun_hours_say(tmp_path):
    r = lightsolver.annual(str(open_site_scene(tmp_path)), str(CHICAGO), photons=400_000)
    m = r["summary"]["grids"][0]["metrics"]
    assert m["sda_percent"]["low"] == 100.0 and m["sda_percent"]["estimate"] == 100.0
    # ASE: occupied hours (stamps 9 … 18) whose direct sun on the horizontal exceeds 1000 lx,
    # from the sky vectors' sun alone, independently of the coefficients.
    year = lightsolver.sky_vectors(str(CHICAGO))
    occupied = (year["hour"] >= 9) & (year["hour"] <= 18)
    beam = year["sun_direct_normal_lx"] * np.sin(np.radians(np.maximum(year["sun_altitude_deg"], 0)))
    sun_hours = int(np.sum(occupied & (beam > 1000)))
    assert m["cells"]["ase_hours"] == [sun_hours] * 4
    assert m["ase_percent"] == (100.0 if sun_hours > 250 else 0.0)
    direct = r["grids"][0]["direct_sun"]
    assert direct[:, 0] == pytest.approx(beam.astype(np.float32), rel=1e-5, abs=1e-3)


def test_shaded_grid_has_no_sda(tmp_path):
    # Facing down over a black ground: no light reaches its lit side, ever. Enough photons that
    # each patch's zero-hit (Wilson) upper end, root-sum-squared over the 146, stays far below
    # 300 lx at the metrics' level (z ≈ 5.5).
    path = open_site_scene(tmp_path, grid_normal_up=False, ground=0.0)
    r = lightsolver.annual(str(path), str(CHICAGO), photons=4_000_000)
    m = r["summary"]["grids"][0]["metrics"]
    assert m["sda_percent"] == {"estimate": 0.0, "low": 0.0, "high": 0.0}
    assert m["ase_percent"] == 0.0
    assert float(np.max(r["grids"][0]["mean"])) == 0.0


def test_sda_interval_covers_a_16_times_longer_trace():
    # The room turned so that its window faces north-east: partly daylit, sDA neither 0 nor 100.
    short = lightsolver.annual(str(ROOM), str(CHICAGO), north_deg=135, photons=500_000, seed=3)
    long = lightsolver.annual(str(ROOM), str(CHICAGO), north_deg=135, photons=8_000_000, seed=4)
    s = short["summary"]["grids"][0]["metrics"]["sda_percent"]
    best = long["summary"]["grids"][0]["metrics"]["sda_percent"]["estimate"]
    assert 0.0 < best < 100.0
    assert s["low"] <= best <= s["high"], (s, best)
    # The per-cell DA intervals of the short trace hold the long trace's estimates: each cell's
    # at 95 % (not simultaneous over the cells), so at most n (1 − c) + 4 sqrt(n c (1 − c))
    # may miss (30 of 300); the long trace's own noise only adds misses.
    da_short = short["summary"]["grids"][0]["metrics"]["cells"]["da_fraction"]
    da_long = long["summary"]["grids"][0]["metrics"]["cells"]["da_fraction"]
    n = len(da_long["estimate"])
    missed = n - sum(lo <= est <= hi for lo, hi, est in
                     zip(da_short["low"], da_short["high"], da_long["estimate"]))
    assert missed <= n * 0.05 + 4 * math.sqrt(n * 0.05 * 0.95), missed


def test_bad_input_is_named_and_writes_nothing(tmp_path):
    out = tmp_path / "never"
    r = cli("annual", str(ROOM), "--weather", str(tmp_path / "missing.epw"), "--out-dir", str(out))
    assert r.returncode != 0 and "missing.epw" in r.stderr
    r = cli("annual", str(ROOM), "--weather", str(CHICAGO), "--mf", "0", "--out-dir", str(out))
    assert r.returncode != 0 and "mf" in r.stderr
    r = cli("annual", str(ROOM), "--weather", str(CHICAGO), "--confidence", "1.5",
            "--out-dir", str(out))
    assert r.returncode != 0 and "confidence" in r.stderr
    no_grid = json.loads(ROOM.read_text())
    no_grid["targets"] = []
    path = tmp_path / "no_grid.scene.json"
    path.write_text(json.dumps(no_grid))
    r = cli("annual", str(path), "--weather", str(CHICAGO), "--out-dir", str(out))
    assert r.returncode != 0 and "target" in r.stderr
    assert not out.exists()
    with pytest.raises(lightsolver.InputError, match="blinds_transmittance"):
        lightsolver.annual(str(ROOM), str(CHICAGO), blinds_transmittance=0.0)


def test_results_reader_views_the_annual_files(tmp_path):
    import lightsolver_results as lr
    out = tmp_path / "out"
    r = cli("annual", str(ROOM), "--weather", str(CHICAGO), "--photons", "1000000",
            "--out-dir", str(out))
    assert r.returncode == 0, r.stderr
    view = lr.read_annual(out / "annual.json")
    assert view.weather.file == CHICAGO.name and view.weather.sky_hours == 4414
    assert view.occupied_hours == 3650 and view.mf == 1 and view.photons == 1000000
    g = view.grid("work plane")
    assert (g.nu, g.nv) == (20, 15) and len(g.cell_da_fraction.estimate) == 300
    assert g.sda_percent.low <= g.sda_percent.estimate <= g.sda_percent.high
    assert g.sda_nominal_verdict in lr.annual.VERDICTS and len(g.en17037) == 3
    assert sorted(g.hours_above) == [100.0, 300.0, 500.0, 750.0, 1000.0, 2000.0, 3000.0]
    hours = lr.load_hours(out / "annual.npz", 0)
    assert hours["mean"].shape == (8760, 300) and hours["direct_sun"].shape == (8760, 300)
    with pytest.raises(lr.ResultsError):
        lr.read_annual({"format": "lightsolver.results/1"})


def test_decide_traces_on_until_the_verdicts_are_decided_or_the_budget_ends():
    def undecided(summary):
        m = summary["grids"][0]["metrics"]
        verdicts = [m["sda_nominal_verdict"], m["sda_preferred_verdict"]]
        verdicts += [e["verdict"] for e in m["en17037"]]
        return sum(v == "undecided" for v in verdicts)

    once = lightsolver.annual(str(ROOM), str(CHICAGO), north_deg=135, photons=300_000, seed=3)
    assert undecided(once["summary"]) > 0  # something to decide
    r = lightsolver.annual(str(ROOM), str(CHICAGO), north_deg=135, photons=300_000, seed=3,
                           decide=True, max_photons=2_400_000)
    t = r["summary"]["trace"]
    assert t["decide"] and t["looks"] >= 2
    assert t["photons"] == min(300_000 * 2 ** (t["looks"] - 1), 2_400_000)
    assert t["stop_reason"] in ("decided", "photons")
    if t["stop_reason"] == "decided":
        assert undecided(r["summary"]) == 0
    else:
        assert t["photons"] == 2_400_000
    assert undecided(r["summary"]) < undecided(once["summary"])


def test_electric_light_beside_the_daylight(tmp_path):
    scene = json.loads(ROOM.read_text())
    scene["luminaires"].append({"name": "panel", "type": "area", "flux_lm": 6000,
                                "corner": [2.4, 1.4, 2.99], "edge1": [1.2, 0, 0],
                                "edge2": [0, 1.2, 0]})
    scene["targets"][0]["requirements"] = {"em_lux": 500}
    path = tmp_path / "lit.scene.json"
    path.write_text(json.dumps(scene))
    r = lightsolver.annual(str(path), str(CHICAGO), photons=300_000, seed=2)
    e = r["summary"]["grids"][0]["electric"]
    assert e["target_lx"] == 500 and e["occupied_hours"] == 3650
    el = e["electric_lx"]
    assert 0 < el["low"] <= el["estimate"] <= el["high"]
    for key, top in (("hours_below_target", 3650), ("mean_output_fraction", 1.0)):
        m = e[key]
        assert 0 <= m["low"] <= m["estimate"] <= m["high"] <= top
    # The daylight grid means, hour by hour, recount the estimate.
    grid = r["grids"][0]
    occupied = (r["month_day_hour"][:, 2] >= 9) & (r["month_day_hour"][:, 2] <= 18)
    assert e["hours_below_target"]["estimate"] == int(np.sum(grid["mean"].mean(axis=1)[occupied]
                                                            < 500))
    # Without electric luminaires there is nothing to report.
    plain = lightsolver.annual(str(open_site_scene(tmp_path)), str(CHICAGO), photons=100_000)
    assert plain["summary"]["grids"][0]["electric"] is None


def test_progress_and_cancel_stop_the_trace(tmp_path):
    scene = str(open_site_scene(tmp_path))
    seen = []

    def progress(done, total):
        seen.append((done, total))
        return len(seen) < 2  # stop after the second batch

    r = lightsolver.annual(scene, str(CHICAGO), photons=4_000_000, progress=progress)
    t = r["summary"]["trace"]
    assert t["stop_reason"] == "cancelled" and 0 < t["photons"] < 4_000_000
    m = r["summary"]["grids"][0]["metrics"]["sda_percent"]
    assert m["low"] <= m["estimate"] <= m["high"]  # a year from the photons traced
    token = lightsolver.CancelToken()
    token.cancel()
    r = lightsolver.annual(scene, str(CHICAGO), photons=4_000_000, cancel=token)
    assert r["summary"]["trace"]["stop_reason"] == "cancelled"

    def boom(done, total):
        raise RuntimeError("from progress")

    with pytest.raises(RuntimeError, match="from progress"):
        lightsolver.annual(scene, str(CHICAGO), photons=4_000_000, progress=boom)


def test_occupancy_is_an_input(tmp_path):
    scene = str(open_site_scene(tmp_path))
    late = lightsolver.annual(scene, str(CHICAGO), photons=200_000, occupied_hours=(13, 20))
    assert late["summary"]["occupancy"]["hours"] == 8 * 365
    assert "12:00-20:00" in late["summary"]["occupancy"]["schedule"]
    mask = np.zeros(8760, dtype=np.uint8)
    mask[4000:4100] = 1
    r = lightsolver.annual(scene, str(CHICAGO), photons=200_000, occupancy=mask.tolist())
    assert r["summary"]["occupancy"]["hours"] == 100
    assert r["summary"]["grids"][0]["metrics"]["occupied_hours"] == 100
    with pytest.raises(lightsolver.InputError, match="occupancy"):
        lightsolver.annual(scene, str(CHICAGO), occupancy=[1] * 10)
    path = tmp_path / "occupancy.txt"
    path.write_text("# one per hour\n" + "1\n" * 8759 + "2\n")
    out = cli("annual", scene, "--weather", str(CHICAGO), "--occupancy", str(path))
    assert out.returncode != 0 and "line 8761" in out.stderr
    out = cli("annual", scene, "--weather", str(CHICAGO), "--occupied-hours", "18-9")
    assert out.returncode != 0 and "--occupied-hours" in out.stderr
