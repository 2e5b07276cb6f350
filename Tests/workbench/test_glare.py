"""Observers (eyes for discomfort glare) in the workbench: the object, its scene entry, Check,
and a traced UGR with its interval and verdict in the results."""
import math
import unittest

import FreeCAD

import lighting
from lighting.objects import observer as observer_mod
from wbtest import DocTestCase, build_office, needs_solver, work_dir


class Observers(DocTestCase):
    def test_scene_entry_and_preset(self):
        doc = build_office()
        eye = lighting.make_observer(doc, (2.5, 0.6, 1.2), view=(0.0, 1.0, 0.3), ugr_max=19.0)
        doc.recompute()
        entry = observer_mod.scene_entry(eye)
        self.assertEqual(entry["type"], "observer")
        self.assertEqual(entry["position"], [2.5, 0.6, 1.2])
        view = entry["view_direction"]  # level: the z of the asked view is dropped
        self.assertAlmostEqual(view[0], 0.0, 9)
        self.assertAlmostEqual(view[1], 1.0, 9)
        self.assertAlmostEqual(view[2], 0.0, 9)
        self.assertEqual(entry["requirements"], {"ugr_max": 19.0})
        # An EN 12464-1 preset fills the limit from the shipped table (UGR_L).
        eye.Activity = "Offices: Technical drawing"
        self.assertEqual(float(eye.UgrMax), 16.0)
        eye.UgrMax = 22.0  # typed by hand: no preset any more
        self.assertEqual(eye.Activity, "Custom")
        with self.assertRaisesRegex(ValueError, "vertical or zero"):
            lighting.make_observer(doc, (1.0, 1.0, 1.2), view=(0.0, 0.0, 1.0))

    def test_check_names_a_bad_limit_and_a_low_eye(self):
        doc = build_office()
        eye = lighting.make_observer(doc, (2.5, 0.6, 0.1), ugr_max=55.0, name="LowEye")
        problems = observer_mod.check(eye)
        levels = sorted(level for level, _ in problems)
        self.assertEqual(levels, ["error", "warning"])
        self.assertTrue(all("LowEye" in text for _, text in problems))

    @needs_solver
    def test_office_observer_gets_a_ugr_with_its_interval_and_verdict(self):
        doc = build_office(photons=200_000)
        analysis = doc.getObject("LightingAnalysis")
        analysis.Decide = False  # exactly the photons asked for
        lighting.make_observer(doc, (2.5, 0.6, 1.2), view=(0.0, 1.0, 0.0), ugr_max=19.0,
                               name="SeatedEye", analysis=analysis)
        result = lighting.analyze(doc, output_dir=work_dir("glare"))
        eye = result["SeatedEye"]
        self.assertEqual(eye.kind, "observer")
        entry = next(t for t in result.data["targets"] if t["name"] == "SeatedEye")
        self.assertGreater(entry["background_luminance_cd_m2"], 0.0)
        if eye.ugr is not None:
            low, high = eye.ugr_ci
            self.assertTrue(math.isfinite(eye.ugr))
            self.assertTrue(low is None or low <= eye.ugr)
            self.assertTrue(high is None or eye.ugr <= high)
        self.assertEqual(eye.verdicts["ugr"]["relation"], "<=")
        self.assertIn(eye.verdict, ("pass", "fail", "undecided"))
        self.assertIn("UGR", result.table())


class ObserverGrids(DocTestCase):
    def test_grid_mode_exports_an_observer_grid_over_the_room(self):
        doc = build_office()
        eye = lighting.make_observer(doc, (2.5, 0.6, 1.2), ugr_max=19.0, name="Eyes")
        room = FreeCAD.BoundBox(0.0, 0.0, 0.0, 5000.0, 4000.0, 3000.0)
        observer_mod.fit_grid(eye, room)  # 0.5 m off the walls, at the eye's height
        eye.GridCellsX, eye.GridCellsY, eye.ViewStep = 3, 2, 45.0
        doc.recompute()
        entry = observer_mod.scene_entry(eye)
        self.assertEqual(entry["type"], "observer_grid")
        self.assertEqual(entry["corner"], [0.5, 0.5, 1.2])
        self.assertEqual(entry["edge1"], [4.0, 0.0, 0.0])
        self.assertEqual(entry["edge2"], [0.0, 3.0, 0.0])
        self.assertEqual(entry["cells"], [3, 2])
        self.assertEqual(entry["view_step_deg"], 45.0)
        self.assertEqual(entry["requirements"], {"ugr_max": 19.0})
        eye.GridMode = False  # back to one eye
        self.assertEqual(observer_mod.scene_entry(eye)["type"], "observer")

    @needs_solver
    def test_office_observer_grid_reports_its_maximum_ugr(self):
        doc = build_office(photons=200_000)
        analysis = doc.getObject("LightingAnalysis")
        analysis.Decide = False
        eye = lighting.make_observer(doc, (1.0, 1.0, 1.2), ugr_max=19.0, name="EyeGrid",
                                     analysis=analysis)
        eye.GridMode, eye.GridLength, eye.GridWidth = True, 3000.0, 2000.0
        result = lighting.analyze(doc, output_dir=work_dir("glare_grid"))
        grid = result["EyeGrid"]
        self.assertEqual(grid.kind, "observer_grid")
        entry = next(t for t in result.data["targets"] if t["name"] == "EyeGrid")
        self.assertEqual(len(entry["observer_grid"]["positions"]), 4)
        self.assertEqual(len(entry["observer_grid"]["view_directions"]), 4)
        values = [u for row in entry["observer_grid"]["ugr"] for u in row if u is not None]
        if grid.ugr is not None:
            self.assertEqual(grid.ugr, max(values))
        self.assertIn("max UGR", result.table())
        self.assertIn(grid.verdict, ("pass", "fail", "undecided"))


if __name__ == "__main__":
    unittest.main()
