"""lightsolver.Simulation, the incremental solver: refine() continues the kept photons bit for
bit, any change starts again, a move equals a fresh solve of the moved scene, bad input is an
InputError naming the field."""
import json
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import lightsolver
from conftest import without_run_facts

ROOM = Path(__file__).resolve().parents[2] / "Examples" / "room" / "room.json"


def without_timing(results: dict, also=()) -> dict:
    """The results dict as JSON text, minus what depends on the clock or the call (seconds, the
    provenance's run facts, and `also`: further provenance keys)."""
    d = without_run_facts({k: v for k, v in results.items() if k not in ("seconds",)}, also)
    for t in d["targets"]:
        for key in [k for k in t if k.startswith("cells_")]:
            t[key] = np.asarray(t[key]).tolist()
    return json.loads(json.dumps(d, sort_keys=True, default=str))


def moved_room(dx_m: float) -> str:
    """room.json with the desk (top and body) moved dx_m along x, as scene JSON text."""
    doc = json.loads(ROOM.read_text())
    for mesh in doc["meshes"]:
        if mesh["name"].startswith("desk"):
            mesh["vertices"] = [[x + dx_m, y, z] for x, y, z in mesh["vertices"]]
    return json.dumps(doc)


def test_refine_in_steps_equals_one_run_bit_for_bit():
    sim = lightsolver.Simulation(str(ROOM))
    one = lightsolver.solve(lightsolver.load_scene(str(ROOM)), photons=300_000, seed=7)
    sim.run(photons=100_000, seed=7)
    assert sim.kept_photons == 100_000
    sim.refine(200_000, seed=7)
    done = []  # photons after each batch: the first batch starts where the kept ones end
    resumed = sim.refine(300_000, seed=7, progress=lambda n, total: done.append(n) or True)
    assert done[0] > 200_000
    assert resumed["photons"] == 300_000
    assert without_timing(resumed) == without_timing(one)


def test_any_change_or_another_seed_starts_again():
    sim = lightsolver.Simulation(str(ROOM))
    sim.run(photons=50_000, seed=3)
    sim.set_luminaire(0, {"type": "area", "flux_lm": 3400, "corner": [1.2, 0.7, 3.0],
                          "edge1": [0, 0.6, 0], "edge2": [0.6, 0, 0]})
    assert sim.kept_photons == 0
    fresh = sim.refine(100_000, seed=3)  # from photon 0: equal to a run of 100 000
    assert without_timing(fresh) == without_timing(sim.run(photons=100_000, seed=3))
    other_seed = sim.refine(150_000, seed=4)
    assert without_timing(other_seed) == without_timing(sim.run(photons=150_000, seed=4))
    # A kept run longer than asked for is not cut: refine starts again.
    assert without_timing(sim.refine(60_000, seed=4)) == without_timing(
        sim.run(photons=60_000, seed=4))


def test_moved_luminaire_then_tracing_is_bit_identical_to_a_fresh_solve():
    panel = {"type": "area", "flux_lm": 5000, "corner": [2.7, 1.7, 3.0],
             "edge1": [0, 0.6, 0], "edge2": [0.6, 0, 0]}
    sim = lightsolver.Simulation(str(ROOM))
    sim.run(photons=100_000, seed=5)
    sim.set_luminaire(1, panel)
    sim.refine(100_000, seed=5)
    moved = sim.refine(200_000, seed=5)
    doc = json.loads(ROOM.read_text())
    doc["luminaires"][1] = {"name": "panel 2", **panel}
    scene = lightsolver.scene_from_json(json.dumps(doc), str(ROOM.parent))
    # Changed in memory, the simulation's scene names no file content; the fresh one does.
    assert moved["provenance"]["scene_sha256"] is None and moved["provenance"]["files"] == []
    identity = ("scene_sha256", "files")
    assert without_timing(moved, identity) == without_timing(
        lightsolver.solve(scene, photons=200_000, seed=5), identity)


def test_moved_mesh_then_tracing_agrees_with_a_fresh_solve_of_the_moved_scene():
    # An instance transform (float) and baked vertices round differently, so the two agree
    # within their noise, not bit for bit: each cell's difference within 5 sigma.
    desks = ["desk body", "desk top"]
    sim = lightsolver.Simulation(str(ROOM), movable_meshes=desks)
    before = sim.run(photons=400_000, seed=2)
    shift = np.eye(4)
    shift[0, 3] = 2.0
    for name in desks:
        sim.set_mesh_transform(sim.mesh_names.index(name), shift)
    assert sim.kept_photons == 0
    moved = sim.refine(400_000, seed=2)
    fresh = lightsolver.solve(lightsolver.scene_from_json(moved_room(2.0), str(ROOM.parent)),
                              photons=400_000, seed=2)
    for a, b, old in zip(moved["targets"], fresh["targets"], before["targets"]):
        if "cells_lux" not in a:
            continue
        sigma = ((a["cells_ci_high_lux"] - a["cells_ci_low_lux"]) / (2 * 1.96))
        sigma_b = ((b["cells_ci_high_lux"] - b["cells_ci_low_lux"]) / (2 * 1.96))
        diff = np.abs(a["cells_lux"] - b["cells_lux"])
        assert np.all(diff <= 5 * np.hypot(sigma, sigma_b) + 1e-9)
        # and the move did change the picture (the desk shades other cells now)
        assert np.max(np.abs(a["cells_lux"] - old["cells_lux"])) > 0


def test_bad_input_is_an_input_error_naming_the_field():
    sim = lightsolver.Simulation(str(ROOM), movable_meshes=["desk top"])
    with pytest.raises(lightsolver.InputError, match="flux_lm"):
        sim.set_luminaire(0, {"type": "point", "position": [1, 1, 1], "flux_lm": -5})
    with pytest.raises(lightsolver.InputError, match="no luminaire 9"):
        sim.set_luminaire(9, {"type": "point", "position": [1, 1, 1], "flux_lm": 5})
    with pytest.raises(lightsolver.InputError, match="not declared movable"):
        sim.set_mesh_transform(0, np.eye(4))
    top = sim.mesh_names.index("desk top")
    with pytest.raises(lightsolver.InputError, match="rigid"):
        sim.set_mesh_transform(top, np.diag([2.0, 2.0, 2.0, 1.0]))
    with pytest.raises(lightsolver.InputError, match="4x4"):
        sim.set_mesh_transform(top, np.eye(3))
    with pytest.raises(lightsolver.InputError, match="movable_meshes"):
        lightsolver.Simulation(str(ROOM), movable_meshes=["sofa"])
    with pytest.raises(lightsolver.InputError, match="threads"):
        lightsolver.Simulation(str(ROOM), threads=-1)
    # a rejected change leaves the kept photons (and the scene) as they were
    sim.run(photons=20_000)
    with pytest.raises(lightsolver.InputError):
        sim.set_luminaire(0, {"type": "point", "position": [1, 1, 1], "flux_lm": float("nan")})
    assert sim.kept_photons == 20_000


def test_cancel_from_another_thread_keeps_what_was_traced():
    sim = lightsolver.Simulation(str(ROOM))
    ticks = []
    timer = threading.Timer(0.3, sim.cancel)
    timer.start()
    start = time.monotonic()
    r = sim.refine(10**10, progress=lambda done, total: ticks.append(done) or True)
    timer.join()
    assert r["partial"] and r["stop_reason"] == "cancelled"
    assert time.monotonic() - start < 5
    assert sim.kept_photons == r["photons"] > 0
