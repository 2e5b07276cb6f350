"""Undecided is actionable (docs/workbench.md, "Undecided requirements"): what deciding costs,
the colour scale set from the requirements, and a new observer's limit from the analysis'
activity."""
import unittest

import lighting
from lighting import colormap, plots
from lighting.objects import analysis as analysis_mod
from lighting.solver import machine
from wbtest import DocTestCase, build_office, needs_solver, work_dir

OFFICE = "Offices: Writing, typing, reading, data processing"


def workplane(doc):
    return [o for o in doc.Objects if o.Label == "Workplane"][0]


class RequirementScale(unittest.TestCase):
    def test_one_and_a_half_times_the_highest_requirement_rounded_up(self):
        self.assertEqual(colormap.requirement_scale([500.0, 150.0]), (0.0, 750.0))
        self.assertEqual(colormap.requirement_scale([572.0]), (0.0, 1000.0))
        self.assertIsNone(colormap.requirement_scale([0.0]))
        self.assertIsNone(colormap.requirement_scale([float("nan")]))


class Facts(unittest.TestCase):
    def test_decided_is_said_only_when_no_row_shown_is_undecided(self):
        from lighting.solver.results import AnalysisResult, TargetResult
        from lighting.taskpanels import results_table

        row = TargetResult("Workplane", "Workplane", "grid", 502.0, 498.0, 506.0,
                           verdict="undecided", undecided=["em"])
        # A light scene's rescaled results keep the traced run's stop reason "decided".
        shown = AnalysisResult([row], photons=16384, seconds=0.034, stop_reason="decided",
                               photons_requested=200000, verdict="undecided")
        text = results_table.facts_text(shown)
        self.assertNotIn("every requirement decided", text)
        self.assertIn("1 requirement(s) undecided", text)
        self.assertIn("in 34 ms", text)  # never "0.00 s"
        self.assertIn("budget 200", text)
        row.verdict, row.undecided = "pass", []
        self.assertIn("every requirement decided, so the run stopped before its budget",
                      results_table.facts_text(shown))
        self.assertEqual(results_table.seconds_text(0.0), "1 ms")
        self.assertEqual(results_table.seconds_text(75.0), "1 min 15 s")


class Decide(DocTestCase):
    def test_a_new_analysis_scale_is_locked_to_its_requirements(self):
        doc = build_office()
        analysis = analysis_mod.find_analysis(doc)
        self.assertEqual(analysis.ScaleMode, "Requirements")
        scale = plots.analysis_scale(analysis)
        self.assertEqual((scale.min_lux, scale.max_lux), (0.0, 750.0))  # 1.5 x 500 lx
        self.assertTrue(plots.scale_note(analysis)[0])
        workplane(doc).RequiredLux = 0.0
        for t in analysis_mod.targets(doc.getObject(analysis.Name)):
            t.RequiredLux = 0.0
        self.assertFalse(plots.scale_note(analysis)[0])  # no requirement: follows each run

    def test_a_new_observer_takes_the_analysis_activity_or_no_limit(self):
        doc = build_office()
        analysis = analysis_mod.find_analysis(doc)
        plain = lighting.make_observer(doc, (2.0, 2.0, 1.2), analysis=analysis)
        self.assertEqual(float(plain.UgrMax), 0.0)  # no activity: "no limit set"
        workplane(doc).Activity = OFFICE
        eye = lighting.make_observer(doc, (2.0, 2.0, 1.2), analysis=analysis)
        self.assertEqual((eye.Activity, float(eye.UgrMax)), (OFFICE, 19.0))
        typed = lighting.make_observer(doc, (2.0, 2.0, 1.2), ugr_max=0.0, analysis=analysis)
        self.assertEqual(float(typed.UgrMax), 0.0)  # an explicit limit is kept

    @needs_solver
    def test_an_undecided_requirement_says_what_deciding_costs_and_a_decide_run_decides_it(self):
        doc = build_office(photons=16384, seed=1)
        analysis = analysis_mod.find_analysis(doc)
        workplane(doc).RequiredLux = 572.0  # just under the ~580 lx the workplane gets
        result = machine.run_analysis(analysis, output_dir=work_dir("decide"))
        target = result["Workplane"]
        self.assertEqual(target.undecided, ["em"])
        photons, seconds = target.to_decide["em"]
        self.assertGreater(photons, 16384)
        self.assertGreater(seconds, 0.0)
        # The panel's Decide: Decide on, a budget of 4 x the forecast (decide_view.budget).
        analysis.Photons = 4 * photons
        analysis.Decide = True
        again = machine.run_analysis(analysis, output_dir=work_dir("decide"))
        self.assertEqual(again["Workplane"].undecided, [])
        self.assertIn(again["Workplane"].verdict, ("pass", "fail"))
        self.assertLessEqual(again.photons, 4 * photons)
        self.assertEqual(again.photons_requested, 4 * photons)  # the budget, in the results
        self.assertEqual(result.photons_requested, 16384)


if __name__ == "__main__":
    unittest.main()
