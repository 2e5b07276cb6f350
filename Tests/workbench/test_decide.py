"""Undecided is actionable (docs/workbench.md, "Undecided requirements"): what deciding costs,
the colour scale set from the requirements, and a new observer's limit from the analysis'
activity."""
import unittest

import lighting
from lighting import colormap, plots
from lighting.objects import analysis as analysis_mod
from lighting.solver import decide, machine
from wbtest import DocTestCase, build_office, needs_solver, work_dir

OFFICE = "Offices: Writing, typing, reading, data processing"


def workplane(doc):
    return [o for o in doc.Objects if o.Label == "Workplane"][0]


#: The office's seed for the runs below. Its workplane gets ~578.8 lx (4e6 photons); 572 lx
#: required must lie inside the interval of the first 16384 photons (undecided) and be decided
#: by a few times more. With next-event estimation (the default) that interval is narrower than
#: photon noise alone (+-7 lx, not +-11), and seed 1's estimate (583.5) puts 572 outside it;
#: seed 6's is 576.1 [569.2, 582.9].
SEED = 6


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


    def test_a_run_with_decide_off_says_so_and_offers_decide(self):
        from lighting.solver.results import AnalysisResult, TargetResult
        from lighting.taskpanels import decide_view

        row = TargetResult("Workplane", "Workplane", "grid", 502.0, 498.0, 506.0,
                           verdict="undecided", undecided=["em"],
                           verdicts={"em": {"required": 500.0, "relation": ">=", "value": 502.0}},
                           to_decide={"em": (1_000_000, 0.5)})
        off = AnalysisResult([row], photons=200000, seconds=0.14, stop_reason="photons",
                             verdict="undecided", data={"decide": False})
        text = decide_view.summary_text(off, limit_s=0.001)
        self.assertIn("Decide requirements was off for this run, so it stopped after its "
                      "200\u202f000 photons", text)
        self.assertIn("Press Decide", text)
        self.assertIn("tick Decide requirements", text)
        self.assertNotIn("continues by itself", text)  # the limit is not why
        off.stop_reason = "accuracy"
        self.assertIn("stopped at its accuracy goal", decide_view.summary_text(off, 0.001))
        row.to_decide = {"em": (None, None)}  # on its bound: no Decide to offer
        text = decide_view.summary_text(off, 0.001)
        self.assertIn("no run can decide it", text)
        self.assertNotIn("Press Decide", text)
        # A decide run beyond the limit: the limit is why.
        row.to_decide = {"em": (1_000_000, 0.5)}
        on = AnalysisResult([row], photons=16384, seconds=0.03, stop_reason="photons",
                            verdict="undecided", data={"decide": True})
        text = decide_view.summary_text(on, limit_s=0.001)
        self.assertIn("more than the 0.001 s a run continues by itself", text)
        self.assertNotIn("was off", text)


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
        doc = build_office(photons=16384, seed=SEED)
        analysis = analysis_mod.find_analysis(doc)
        workplane(doc).RequiredLux = 572.0  # just under the ~579 lx the workplane gets
        # Without the automatic continuation (limit 0): the run stops at its budget.
        result = machine.run_analysis(analysis, output_dir=work_dir("decide"), decide_limit_s=0)
        target = result["Workplane"]
        self.assertEqual(target.undecided, ["em"])
        photons, seconds = target.to_decide["em"]
        self.assertGreater(photons, 16384)
        self.assertGreater(seconds, 0.0)
        # The panel's Decide: Decide on, a budget of 4 x the forecast (decide_view.budget).
        analysis.Photons = 4 * photons
        analysis.Decide = True
        again = machine.run_analysis(analysis, output_dir=work_dir("decide"), decide_limit_s=0)
        self.assertEqual(again["Workplane"].undecided, [])
        self.assertIn(again["Workplane"].verdict, ("pass", "fail"))
        self.assertLessEqual(again.photons, 4 * photons)
        self.assertEqual(again.photons_requested, 4 * photons)  # the budget, in the results
        self.assertEqual(result.photons_requested, 16384)


    @needs_solver
    def test_a_decide_run_goes_on_by_itself_within_the_limit(self):
        """The default run decides: a decide run left undecided at its budget traces again
        with the Decide budget when that takes at most the limit, and the results are the
        second run's (decided); the photons traced count both passes."""
        doc = build_office(photons=16384, seed=SEED)
        analysis = analysis_mod.find_analysis(doc)
        workplane(doc).RequiredLux = 572.0
        first = machine.run_analysis(analysis, output_dir=work_dir("decide"), decide_limit_s=0)
        plan = decide.plan(first)
        self.assertIsNotNone(plan)
        self.assertEqual(plan.budget, decide.budget_for(first["Workplane"].to_decide["em"][0],
                                                        16384))
        self.assertLess(plan.seconds, 30.0)
        self.assertTrue(plan.within(30.0))
        lines = []
        job = machine.AnalysisRun(analysis, work_dir("decide"),
                                  lambda level, text: lines.append(text), decide_limit_s=30.0)
        job.check()
        job.prepare()
        job.solve()
        result = job.apply()
        self.assertTrue(job.continued)
        self.assertEqual(result["Workplane"].undecided, [])
        self.assertIn(result["Workplane"].verdict, ("pass", "fail"))
        self.assertEqual(result.photons_requested, plan.budget)  # the second pass' budget
        self.assertEqual(job.photons_traced, 16384 + int(result.photons))
        self.assertTrue(any("tracing again with a budget of" in t for t in lines), lines)
        # The scene file reproduces the stored run (its photons: the second pass' budget).
        import json
        with open(job.scene_file, encoding="utf-8") as stream:
            self.assertEqual(json.load(stream)["settings"]["photons"], plan.budget)

    @needs_solver
    def test_the_default_run_decides_a_layout_tool_result_close_to_its_requirement(self):
        """A 3 x 2 layout made by the layout tool, its workplane required just under what it
        gets: the default budget (200 000 photons, Decide on) leaves it undecided, and the
        default run goes on by itself and decides it."""
        import test_layout as layouts

        doc, ceiling, face = layouts._office_without_luminaires()
        layouts._layout(doc, ceiling, face, margin_x_m=1.0, margin_y_m=1.0)
        analysis = analysis_mod.find_analysis(doc)
        analysis.Photons, analysis.Decide, analysis.TargetAccuracy = 200000, True, 0.0
        probe = machine.run_analysis(analysis, output_dir=work_dir("decide"), decide_limit_s=0)
        em = probe["Workplane"].mean_lux
        lo = probe["Workplane"].ci_low_lux
        # Required inside the default run's interval (the same seed traces the same photons):
        # undecided at the budget, as the 502 lx against 500 lx.
        workplane(doc).RequiredLux = round(em - 0.6 * (em - lo), 1)
        workplane(doc).RequiredUniformity = 0.0
        first = machine.run_analysis(analysis, output_dir=work_dir("decide"), decide_limit_s=0)
        self.assertEqual(first["Workplane"].undecided, ["em"],
                         f"Em {first['Workplane'].mean_lux} [{first['Workplane'].ci_low_lux}, "
                         f"{first['Workplane'].ci_high_lux}] vs {workplane(doc).RequiredLux}")
        result = machine.run_analysis(analysis, output_dir=work_dir("decide"))  # the default
        self.assertEqual(result["Workplane"].undecided, [])
        self.assertGreater(result.photons, 200000)

    @needs_solver
    def test_beyond_the_limit_the_run_stops_and_says_why(self):
        doc = build_office(photons=16384, seed=SEED)
        analysis = analysis_mod.find_analysis(doc)
        workplane(doc).RequiredLux = 572.0
        lines = []
        result = machine.run_analysis(analysis, output_dir=work_dir("decide"),
                                      log=lambda level, text: lines.append(text),
                                      decide_limit_s=1e-6)
        self.assertEqual(result["Workplane"].undecided, ["em"])
        self.assertEqual(result.photons, 16384)
        said = [t for t in lines if "more than the 1e-06 s a run continues by itself" in t]
        self.assertTrue(said and "deciding needs up to" in said[0] and "press Decide" in said[0],
                        lines)

    def test_plan_of_a_value_on_its_bound_has_no_budget(self):
        from lighting.solver.results import AnalysisResult, TargetResult

        row = TargetResult("Workplane", "Workplane", "grid", 500.0, 490.0, 510.0,
                           verdict="undecided", undecided=["em"], to_decide={"em": (None, None)})
        plan = decide.plan(AnalysisResult([row], photons=1000, seconds=0.01))
        self.assertEqual((plan.budget, plan.undecidable), (0, [("Workplane", "em")]))
        self.assertFalse(plan.within(30.0))
        self.assertIn("no run can decide it", machine.why_not(plan, 30.0))
        row.to_decide = {"em": (1_000_000, 0.5)}
        plan = decide.plan(AnalysisResult([row], photons=1000, seconds=0.01))
        self.assertEqual((plan.budget, plan.seconds), (4_000_000, 2.0))
        self.assertTrue(plan.within(30.0) and not plan.within(1.0))
        self.assertIn("4.0\u202fM photons, about 2.0 s, more than the 1 s",
                      machine.why_not(plan, 1.0))
        self.assertIsNone(decide.plan(AnalysisResult([], photons=1000)))


if __name__ == "__main__":
    unittest.main()
