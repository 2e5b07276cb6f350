"""Annual daylight in the workbench (objects/annual.py, solver/annual.py, annual_results.py):
the object and its checks, the scene it exports, a traced year (Chicago, a small photon count)
stored on the object and read back through lightsolver_results.read_annual, the per-cell maps,
and the stored results after save and reopen (docs/workbench-daylight.md, "Annual daylight")."""
import hashlib
import json
import os

import FreeCAD

import lighting
from lighting import annual_results
from lighting.messages import CheckError
from lighting.objects import annual as annual_mod
from lighting.objects.analysis import find_analysis
from lighting.solver import annual as annual_run
from lighting.solver.results import reader
from wbtest import DocTestCase, REPO, build_office, load_scene, needs_solver, work_dir

CHICAGO = os.path.join(REPO, "Tests/native/sun/data/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw")
PHOTONS = 100000


def office_with_annual(sky: bool = True, weather: str = CHICAGO):
    """The example office (a south window, the work-plane grid) with a Sky and an annual
    daylight analysis in its analysis."""
    import office_model

    doc = build_office(photons=20000)
    analysis = find_analysis(doc)
    sky_obj = lighting.make_sky(doc, analysis=analysis) if sky else None
    annual = lighting.make_annual_daylight(analysis, weather, photons=PHOTONS)
    doc.recompute()
    return doc, analysis, sky_obj, annual, dict(office_model.OBJECTS)


class AnnualObject(DocTestCase):
    def test_defaults_and_place_in_the_analysis(self):
        doc, analysis, _, annual, _ = office_with_annual()
        self.assertIn(annual, analysis.Group)
        self.assertEqual(annual_mod.analysis_of(annual), analysis)
        self.assertEqual(annual_mod.mf(annual), 1)
        self.assertEqual(annual.Map, "DA300")
        self.assertEqual(annual.Status, "not run")
        self.assertEqual(list(annual.SummaryLines), [])
        self.assertEqual(annual_mod.check(annual), [])
        self.assertIsNone(annual_run.is_current(annual))

    def test_checks_name_the_problem(self):
        doc, analysis, _, annual, _ = office_with_annual()
        annual.WeatherFile = ""
        annual.BlindsTransmittance = 1.5
        texts = " ".join(t for _, t in annual_mod.check(annual))
        self.assertIn("no weather file", texts)
        self.assertIn("BlindsTransmittance", texts)
        annual.WeatherFile = os.path.join(work_dir("annual"), "missing.epw")
        self.assertIn("does not exist", " ".join(t for _, t in annual_mod.check(annual)))

    @needs_solver
    def test_without_a_sky_the_check_says_so(self):
        doc, analysis, _, annual, _ = office_with_annual(sky=False)
        job = annual_run.AnnualRun(annual, work_dir("annual"))
        with self.assertRaises(CheckError) as caught:
            job.check()
        self.assertIn("exactly one Sky", str(caught.exception))
        self.assertEqual(annual.Status, "check failed")

    @needs_solver
    def test_daylight_only_needs_no_luminaire(self):
        doc, analysis, _, annual, _ = office_with_annual()
        for lum in list(analysis.Group):
            if getattr(lum.Proxy, "Type", "") == "Lighting::Luminaire":
                doc.removeObject(lum.Name)
        doc.recompute()
        job = annual_run.AnnualRun(annual, work_dir("annual"))
        report = job.check()  # no "No luminaires" error: the annual run traces daylight only
        # The Sky's default site is Paris: the Chicago file is another place's year.
        warnings = [m.text for m in report.messages if m.level == "warning"]
        self.assertTrue(any("far from the site" in w and "Chicago" in w for w in warnings),
                        warnings)
        path = job.prepare()
        scene = load_scene(path)
        skies = [lum for lum in scene["luminaires"] if lum["type"] == "sky"]
        self.assertEqual(len(skies), 1)
        self.assertEqual(len(skies[0]["portals"]), 1)
        self.assertEqual(os.path.basename(os.path.dirname(path)), annual_run.SUBFOLDER)


class AnnualCancel(DocTestCase):
    @needs_solver
    def test_cancel_stops_the_trace_and_changes_nothing(self):
        from lighting.messages import CancelledError

        doc, analysis, _, annual, _ = office_with_annual()
        annual.Photons = 2_000_000_000  # far more than the test waits for
        doc.recompute()
        job = annual_run.AnnualRun(annual, work_dir("annual_cancel"))
        job.check()
        job.prepare()
        job.start()
        job.cancel()
        self.assertTrue(job.wait(120.0), "the cancelled trace did not stop")
        self.assertIsInstance(job.error, CancelledError)
        self.assertEqual(annual.SummaryJson, "")
        self.assertEqual(list(annual.SummaryLines), [])


class AnnualRunStored(DocTestCase):
    @needs_solver
    def test_a_year_is_stored_read_and_mapped(self):
        doc, analysis, sky, annual, names = office_with_annual()
        sky.North = 30.0  # no Arch Site: the Sky's North is the run's
        sky.Latitude, sky.Longitude, sky.TimeZone = 41.98, -87.92, -6.0  # Chicago
        doc.recompute()
        out = work_dir("annual")
        logged = []
        summary = lighting.run_annual(annual, out, log=lambda level, text: logged.append(text))
        self.assertFalse([t for t in logged if "far from the site" in t])
        typed = annual_results.read(summary)
        self.assertIsNotNone(typed)
        digest = hashlib.sha256(open(CHICAGO, "rb").read()).hexdigest()
        self.assertEqual(annual.WeatherSha256, digest)
        self.assertEqual(annual.WeatherName, os.path.basename(CHICAGO))
        self.assertEqual(typed.weather.sha256, digest)
        self.assertEqual(typed.north_deg, 30.0)
        self.assertEqual(annual.NorthUsed, 30.0)
        self.assertEqual(typed.photons, PHOTONS)
        self.assertEqual(annual.Status, "done")
        self.assertTrue(annual_run.is_current(annual))
        grid = annual_results.grid_of(typed, names["workplane"])
        self.assertIsNotNone(grid)
        cells = grid.nu * grid.nv
        for iv in (grid.sda_percent, grid.da_fraction, grid.udi_useful_fraction):
            self.assertLessEqual(iv.low, iv.estimate)
            self.assertLessEqual(iv.estimate, iv.high)
        for kind in ("DA300", "UDI 100-2000 lx", "ASE hours", "sDA verdict"):
            values = annual_results.cell_values(grid, kind)
            self.assertEqual(len(values), cells, kind)
            scale = annual_results.scale(kind, values)
            self.assertTrue(all(scale.min_lux <= v <= scale.max_lux for v in values), kind)
        # The sDA verdicts agree with the cells' DA300 intervals around 50 %.
        da = grid.cell_da_fraction
        for verdict, low, high in zip(grid.cell_sda_verdict, da.low, da.high):
            if verdict == "pass":
                self.assertGreaterEqual(low, 0.5)
            elif verdict == "fail":
                self.assertLess(high, 0.5)
        # The panel's lines: sDA with its interval and verdicts, ASE, UDI, EN 17037, weather.
        text = "\n".join(annual.SummaryLines)
        for words in ("sDA300/50%: ", "LM-83 nominal", "ASE1000,250h: ", "mean UDI 100-2000 lx",
                      "EN 17037 minimum", "Chicago Ohare", digest[:16],
                      "electric beside daylight: daylight below"):  # the office's luminaires
            self.assertIn(words, text)
        # The files beside the scene: the summary and the hourly values (the CLI's layout).
        folder = annual.OutputFolder
        with open(os.path.join(folder, "annual.json"), encoding="utf-8") as stream:
            self.assertEqual(annual_results.read(json.load(stream)).weather.sha256, digest)
        index = [g.name for g in typed.grids].index(names["workplane"])
        hours = reader().load_hours(os.path.join(folder, "annual.npz"), index)
        self.assertEqual(hours["mean"].shape, (8760, cells))
        self.assertTrue((hours["low"] <= hours["mean"]).all())
        self.assertTrue((hours["mean"] <= hours["high"]).all())
        # Saved and reopened: the summary is kept, its lines derived again, still current.
        path = os.path.join(out, "annual.FCStd")
        doc.saveAs(path)
        lines = list(annual.SummaryLines)
        FreeCAD.closeDocument(doc.Name)
        doc = FreeCAD.openDocument(path)
        again = annual_mod.all_in(doc)[0]
        self.assertEqual(list(again.SummaryLines), lines)
        self.assertTrue(annual_run.is_current(again))
        # An edit of the model leaves them stale.
        wp = doc.getObject(names["workplane"])
        wp.WorkplaneHeight = float(wp.WorkplaneHeight) + 100.0
        doc.recompute()
        self.assertFalse(annual_run.is_current(again))


class AnnualMaps(DocTestCase):
    def test_no_or_foreign_summary_reads_as_none(self):
        self.assertIsNone(annual_results.read(None))
        self.assertIsNone(annual_results.read({"format": "lightsolver.results/1"}))
        self.assertEqual(annual_results.summary_lines(None), [])

    def test_the_verdict_map_has_three_distinct_colours(self):
        scale = annual_results.scale("sDA verdict", [0.0, 1.0, 2.0])
        colours = [scale.colour(annual_results.VERDICT_VALUE[v])
                   for v in ("fail", "undecided", "pass")]
        self.assertEqual(len(set(colours)), 3)
        self.assertEqual(scale.ticks(), [0.0, 1.0, 2.0])
        # ASE: at least 500 h, so LM-83's 250 h sits mid-scale or lower.
        self.assertEqual(annual_results.scale("ASE hours", [10.0, 40.0]).max_lux, 500.0)
        self.assertGreaterEqual(annual_results.scale("ASE hours", [1800.0]).max_lux, 1800.0)
        with self.assertRaises(ValueError):
            annual_results.cell_values(None, "Run illuminance")
