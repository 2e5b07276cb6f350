"""The one Python results reader (NativeSolver/python/lightsolver_results): schema-checked, the
legacy fallbacks in one migration step that says what it did, each target type read once; found
by FreeCAD's /usr/bin/python3 from the build folder and from the source tree."""
import copy
import json
import os
import subprocess

import pytest

import lightsolver
import lightsolver_results as reader
from conftest import SOURCE_DIR

GOLDEN = SOURCE_DIR / "Tests" / "golden"


def golden(name):
    return json.loads((GOLDEN / f"{name}.results.json").read_text())


@pytest.mark.parametrize("name", ["room", "office"])
def test_current_results_read_without_migration(name):
    doc = golden(name)
    read = reader.read(doc)
    assert read.notes == [] and read.traced_flux
    assert [t.name for t in read.targets] == [t["name"] for t in doc["targets"]]
    for t, entry in zip(read.targets, doc["targets"]):
        assert (t.em.value, t.em.low, t.em.high) == (
            entry["mean_lux"], entry["ci_low_lux"], entry["ci_high_lux"])
        if t.is_grid:
            assert t.emin.value == entry["min_lux"] and t.u0.value == entry["uniformity"]
            # Every grid has its statistics' intervals (since issue 24), judged or not.
            assert (t.ud.value, t.ud.low, t.ud.high) == (
                entry["ud"], entry["ud_ci_low"], entry["ud_ci_high"])
            assert t.emin.low <= t.emin.value <= t.emin.high
    assert sum(lum.emitted_flux_lm for lum in read.luminaires) == pytest.approx(
        doc["total_flux_lm"], rel=1e-12)
    assert doc == golden(name)  # the caller's document is left as it was


def test_the_migration_fills_what_older_solvers_left_out_and_says_so():
    doc = golden("room")
    grid = doc["targets"][1]
    for key in [k for k in grid if k.startswith(("min_", "max_", "uniformity", "ud"))]:
        grid.pop(key)  # a solver from before the grid statistics (and their intervals)
    doc.pop("luminaires")
    scene = json.loads((SOURCE_DIR / "Examples" / "room" / "room.json").read_text())
    read = reader.read(doc, scene, lambda lum: 2.0 * lum["flux_lm"])
    lux = [c["lux"] for c in grid["cells"]]
    workplane = read["workplane"]
    assert (workplane.emin.value, workplane.emax.value) == (min(lux), max(lux))
    assert workplane.u0.value == min(lux) / grid["mean_lux"]
    assert any("grid statistics derived from the cells" in n and "workplane" in n
               for n in read.notes)
    assert reader.DERIVED_FLUX_NOTE in read.notes and not read.traced_flux
    assert [lum.emitted_flux_lm for lum in read.luminaires] == [
        2.0 * lum["flux_lm"] for lum in scene["luminaires"]]
    assert all(lum.tilt_factor == 1.0 for lum in read.luminaires)
    # Without a scene the luminaires stay absent (nothing to derive them from).
    assert reader.read(doc).luminaires == []


def test_schema_problems_raise_or_become_notes():
    doc = golden("office")
    doc["targets"][0]["mean_lux"] = "bright"
    with pytest.raises(reader.ResultsError, match="targets/0/mean_lux"):
        reader.read(doc)
    lenient = reader.read(doc, strict=False)
    assert any(n.startswith("schema: targets/0/mean_lux") for n in lenient.notes)
    assert lenient.targets[0].em.value is None
    with pytest.raises(reader.ResultsError, match="format"):
        reader.read(dict(doc, format="lightsolver.results/0"), strict=False)
    assert reader.check(golden("office")) == []


def test_an_observer_grid_is_read_as_one(room_scene):
    scene = lightsolver.load_scene(str(room_scene))
    scene.add_target("eyes", "observer_grid", corner=[0.5, 0.5, 1.2], edge1=[5.0, 0, 0],
                     edge2=[0, 3.0, 0], cells=[2, 2], view_step_deg=90)
    raw = lightsolver.solve(scene, photons=50_000, seed=3)
    read = reader.read(reader.plain(raw))
    eyes = read["eyes"]
    entry = raw["targets"][-1]
    assert eyes.is_glare and not eyes.is_grid
    assert (eyes.ugr.value, eyes.ugr.low, eyes.ugr.high) == (
        entry["ugr"], entry["ugr_ci_low"], entry["ugr_ci_high"])
    grid = eyes.observer_grid
    assert grid.points == 16 and len(grid.ugr) == 4
    at = entry["observer_grid"]["max_at"]
    assert grid.max_at == (at["position"], at["direction"])
    assert grid.ugr[at["position"]][at["direction"]] == entry["ugr"]
    assert [lum.name for lum in read.luminaires] == [lum["name"] for lum in raw["luminaires"]]


@pytest.mark.parametrize("where", ["build", "source"])
def test_freecads_python_imports_it_and_finds_the_schema(where):
    """/usr/bin/python3 (FreeCAD's embedded interpreter) with only the reader's folder on the
    path: the build folder's copy has the schema beside it, the source tree's finds
    docs/schemas."""
    folder = (os.path.dirname(os.path.dirname(reader.__file__)) if where == "build"
              else str(SOURCE_DIR / "NativeSolver" / "python"))
    code = ("import lightsolver_results as r, sys; s = r.schema(); "
            "print(r.__file__); sys.exit(0 if s and s['title'] else 1)")
    out = subprocess.run(["/usr/bin/python3", "-S", "-c", code], capture_output=True, text=True,
                         env={"PYTHONPATH": folder}, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith(folder)


def test_every_target_type_of_the_solver_is_read(tmp_path, room_scene):
    """The reader knows every target type the solver writes (a type added to the solver
    without a reading here fails this test), and says so of a type it does not know."""
    scene = json.loads(room_scene.read_text())
    known = {t["type"] for t in scene["targets"]} | {"observer", "observer_grid"}
    types = getattr(lightsolver, "target_types", None)  # the solver's rows, where exported
    if types is not None:
        known |= {str(row.get("name") or row.get("type")) if isinstance(row, dict) else str(row)
                  for row in types()}
    assert known <= set(reader.READ_TYPES), known - set(reader.READ_TYPES)
    doc = golden("room")
    doc["targets"][0]["type"] = "daylight_factor"
    read = reader.read(doc, strict=False)
    assert any("'daylight_factor' is unknown to this reader" in n for n in read.notes)
    assert read.targets[0].em.value == doc["targets"][0]["mean_lux"]


def test_the_run_facts_cells_and_overall_verdict_are_typed():
    """What the workbench read by hand before (run facts, cells, the overall verdict, whether
    a rescale is possible) comes from the reader, equal to the document's values."""
    doc = golden("lamps.embree")
    read = reader.read(doc)
    run = read.run
    assert (run.photons, run.photons_requested, run.partial, run.stop_reason) == (
        doc["photons"], doc["photons_requested"], doc["partial"], doc["stop_reason"])
    assert (run.seconds, run.backend, run.confidence, run.seed, run.decide) == (
        doc["seconds"], doc["backend"], doc["confidence"], doc["seed"], doc["decide"])
    assert run.warnings == doc["warnings"]
    assert read.verdict == doc["verdict"] == "fail"
    assert read.has_contributions
    grids = 0
    for t, entry in zip(read.targets, doc["targets"]):
        cells = entry.get("cells", [])
        assert len(t.cell_values) == len(cells)
        for key in ("lux", "ci_low_lux", "ci_high_lux", "hits"):
            assert getattr(t.cell_values, key) == [c[key] for c in cells]
        grids += bool(cells)
        assert t.verdict == entry["verdict"] and not t.estimated
        for name, verdict in entry["verdicts"].items():
            assert t.verdict_of(name) == verdict["verdict"]
            cost = verdict.get("to_decide") or {}
            assert t.to_decide(name) == (cost.get("photons"), cost.get("seconds"))
        assert t.verdict_of("no such requirement") is None
        assert t.to_decide("no such requirement") == (None, None)
    assert grids == 2
    plain_room = reader.read(golden("room"))
    assert plain_room.verdict is None and not plain_room.has_contributions
    assert plain_room.run.decide is False and plain_room.run.photons == golden("room")["photons"]


def test_what_deciding_an_undecided_requirement_costs_is_typed():
    """to_decide: (photons, seconds) of an undecided verdict; None where the solver gave null
    (the value on the bound); (None, None) for a decided one."""
    doc = golden("lamps.embree")
    entry = copy.deepcopy(doc["targets"][0])
    name = next(iter(entry["verdicts"]))
    entry["verdicts"][name].update(verdict="undecided",
                                   to_decide={"photons": 253821, "seconds": 0.14})
    t = reader.read(dict(doc, targets=[entry]), strict=False).targets[0]
    assert t.verdict_of(name) == "undecided" and t.to_decide(name) == (253821, 0.14)
    entry["verdicts"][name]["to_decide"] = {"photons": None, "seconds": None}
    t = reader.read(dict(doc, targets=[entry]), strict=False).targets[0]
    assert t.to_decide(name) == (None, None)


def test_requirements_the_solver_did_not_judge_are_estimated_by_the_migration():
    """Results without the solver's verdicts (an older solver, or requirements set after the
    run) with requirements given: each is judged on its point estimate, marked estimated and
    said in the notes; the migrated document still validates, the caller's is unchanged."""
    doc = golden("room")
    desk, grid = doc["targets"][0]["mean_lux"], doc["targets"][1]
    wanted = {"desk top": {"em_lux": desk, "u0": 0.5},  # at the bound: pass; u0: not a grid's
              "workplane": {"em_lux": grid["mean_lux"] - 1.0,
                            "u0": grid["uniformity"] + 0.01, "emin_lux": grid["min_lux"],
                            "ud": 1.0, "ugr_max": 19.0, "task": "office"},
              "floor": {}}
    read = reader.read(doc, requirements=wanted)
    desk_t, grid_t, floor_t = read.targets
    assert desk_t.estimated and desk_t.verdict == "pass" and desk_t.requirements == {
        "em_lux": desk}
    assert desk_t.verdicts["em"] == {"verdict": "pass", "value": desk, "ci_low": desk,
                                     "ci_high": desk, "required": desk, "relation": ">="}
    assert grid_t.estimated and grid_t.verdict == "fail"
    assert {k: grid_t.verdict_of(k) for k in ("em", "u0", "emin", "ud", "ugr")} == {
        "em": "pass", "u0": "fail", "emin": "pass", "ud": "fail", "ugr": None}
    assert floor_t.verdict is None and not floor_t.estimated
    assert read.verdict is None  # the overall verdict is the solver's alone
    assert [n for n in read.notes if n.startswith(reader.ESTIMATED_NOTE)] == [
        reader.ESTIMATED_NOTE + "desk top, workplane"]
    assert reader.check(read.doc) == []
    assert doc == golden("room")
    # Without requirements nothing is estimated (the report's reading is unchanged).
    assert all(t.verdict is None for t in reader.read(doc).targets)


def test_the_solvers_verdicts_are_never_replaced_by_estimates():
    doc = golden("lamps.embree")
    wanted = {t["name"]: {"em_lux": 1e9, "u0": 0.99, "ugr_max": 1.0} for t in doc["targets"]}
    read = reader.read(doc, requirements=wanted)
    assert not any(n.startswith(reader.ESTIMATED_NOTE) for n in read.notes)
    for t, entry in zip(read.targets, doc["targets"]):
        assert not t.estimated and t.verdict == entry["verdict"]
        assert t.verdicts == entry["verdicts"] and t.requirements == entry["requirements"]


def test_a_glare_limit_is_estimated_on_the_ugr():
    doc = golden("lamps.embree")
    seated = next(t for t in doc["targets"] if t["name"] == "seated")
    for key in ("requirements", "verdicts", "verdict"):
        seated.pop(key)
    ugr = seated["ugr"]
    for limit, word in ((ugr + 0.5, "pass"), (ugr - 0.5, "fail")):
        eye = reader.read(doc, requirements={"seated": {"ugr_max": limit, "em_lux": 1.0}},
                          strict=False)["seated"]
        assert eye.estimated and eye.verdict == word and set(eye.verdicts) == {"ugr"}
        assert eye.verdicts["ugr"]["relation"] == "<="


def test_daylight_factor_grids_are_read_with_their_statistics():
    """A daylight-factor grid's block as the reader's view: the sky, E_out, the mean, min, p50
    and p95 with their intervals, the cells; an illuminance target has none."""
    scene = lightsolver.load_scene(
        str(SOURCE_DIR / "Examples" / "daylight" / "side_lit_room.scene.json"))
    doc = lightsolver.solve(scene, photons=50000, seed=4, backend="embree")
    results = reader.read(doc)
    grid, floor = results.targets[0], results.targets[1]
    df = grid.daylight_factor
    assert df is not None and floor.daylight_factor is None
    block = doc["targets"][0]["daylight_factor"]
    assert df.sky == "overcast sky" and df.outside_illuminance_lx == 10000
    assert (df.p50.value, df.p50.low, df.p50.high) == (
        block["p50_percent"], block["p50_ci_low_percent"], block["p50_ci_high_percent"])
    assert df.min.low <= df.min.value <= df.p95.value <= df.p50.value
    assert df.cells == [c["percent"] for c in block["cells"]]
    assert grid.verdict_of("df_target") in ("pass", "fail", "undecided")


def test_sunlight_exposure_view():
    """The results' EN 17037 sunlight exposure as a typed view; None without it."""
    from lightsolver_results.sunlight import sunlight_view

    assert sunlight_view({}) is None
    view = sunlight_view({"sunlight_exposure": {
        "date": "2026-03-21", "step_minutes": 1, "min_elevation_deg": 11,
        "points": [{"name": "South", "hours": 3.2, "level": "medium",
                    "periods": [["09:14", "12:26"]]},
                   {"name": "North", "hours": 0.0, "level": "none", "periods": []}]}})
    assert (view.date, view.step_minutes, view.min_elevation_deg) == ("2026-03-21", 1.0, 11.0)
    south, north = view.points
    assert (south.name, south.level, south.periods) == ("South", "medium", (("09:14", "12:26"),))
    assert south.duration_text() == "3 h 12 min"
    assert (north.hours, north.level, north.duration_text()) == (0.0, "none", "0 h 00 min")
