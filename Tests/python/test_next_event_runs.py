"""Next-event estimation (the default, `auto`) in runs that stop early: the direct parts start
at the default points before the photons and are refined to the run's plan after them
(docs/statistics.md, "Next-event estimation", "When they are traced"). A stopped run keeps whole
parts with honest intervals; a run that is not stopped is the same for a seed."""
import json

import lightsolver
import numpy as np
from test_study import K, Z95, exact_cells, closed_form_scene, half_widths

PLANNED = "stopped before its direct light was sampled as planned"


def point_over_black(settings=None):
    """test_study's closed form (a point source over a black floor) with next_event at its
    default: every cell's light is the direct part alone."""
    doc = closed_form_scene()
    doc["settings"] = settings or {}
    return lightsolver.scene_from_json(json.dumps(doc))


def test_a_run_stopped_during_its_photons_keeps_the_coarse_direct_parts():
    scene = point_over_black()
    # 10^8 photons plan the finest points (16 x the default per side); the first batch stops it.
    stopped = lightsolver.solve(scene, photons=100_000_000, seed=3,
                                progress=lambda done, total: False)
    assert stopped["partial"] and stopped["stop_reason"] == "cancelled"
    assert 0 < stopped["photons"] < 100_000_000
    assert any(PLANNED in w for w in stopped["warnings"]), stopped["warnings"]
    assert "next_event_direct" in stopped["effects"]["simulated"]
    grid = stopped["targets"][0]
    # The parts are the default points' (what a plain run of 10^4 photons plans), whole ...
    plain = lightsolver.solve(scene, photons=10_000, seed=3)
    assert not any(PLANNED in w for w in plain["warnings"])
    assert np.array_equal(grid["cells_lux"], plain["targets"][0]["cells_lux"])
    assert np.array_equal(grid["cells_ci_high_lux"], plain["targets"][0]["cells_ci_high_lux"])
    # ... and honest: every cell within K sigma of the closed form.
    exact = exact_cells([-1, -1], 2.0, 10)
    sigma = half_widths(grid) / Z95
    assert np.all(sigma > 0)
    assert np.all(np.abs(grid["cells_lux"] - exact) <= K * sigma)


def test_the_planned_parts_are_finer_and_the_same_for_a_seed():
    scene = point_over_black()
    coarse = lightsolver.solve(scene, photons=10_000, seed=3)["targets"][0]
    runs = [lightsolver.solve(scene, photons=200_000, seed=3)["targets"][0] for _ in range(2)]
    assert np.array_equal(runs[0]["cells_lux"], runs[1]["cells_lux"])
    assert np.array_equal(runs[0]["cells_ci_low_lux"], runs[1]["cells_ci_low_lux"])
    # 2e5 photons plan 25 x the default points per cell (scale 5): intervals ~5x narrower at
    # least, in the mean over cells (stratified: the variance falls at least as 1/points).
    ratio = np.mean(half_widths(coarse)) / np.mean(half_widths(runs[0]))
    assert ratio > 4.0, ratio


def test_a_run_stopped_before_its_direct_light_traces_none_and_says_why():
    scene = point_over_black()
    token = lightsolver.CancelToken()
    token.cancel()
    r = lightsolver.solve(scene, photons=100_000_000, seed=3, cancel=token)
    assert r["partial"] and r["photons"] == 0
    skipped = {s["effect"]: s["reason"] for s in r["effects"]["skipped"]}
    assert "stopped before its direct light was traced" in skipped["next_event_direct"]
    grid = r["targets"][0]
    assert np.all(np.isfinite(grid["cells_ci_high_lux"]))
    assert np.all(grid["cells_ci_low_lux"] <= grid["cells_lux"])
    assert np.all(grid["cells_lux"] <= grid["cells_ci_high_lux"])


def test_a_run_its_time_limit_ends_gets_the_parts_of_the_photons_it_traced():
    """Not the 10^9 photons' finest points: the parts of a plain run of the photons traced."""
    scene = point_over_black()
    limited = lightsolver.solve(scene, photons=1_000_000_000, seed=3, max_seconds=0.2)
    assert limited["stop_reason"] == "time" and not limited["partial"]
    plain = lightsolver.solve(scene, photons=limited["photons"], seed=3)
    assert not any(PLANNED in w for w in limited["warnings"])
    for key in ("cells_lux", "cells_ci_low_lux", "cells_ci_high_lux"):
        assert np.array_equal(limited["targets"][0][key], plain["targets"][0][key])
