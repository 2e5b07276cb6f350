"""Light scenes: control groups on luminaires, light scene objects, and results shown by
rescaling one run traced with contributions (no tracing when switching or dimming)."""
import math
import unittest

import lighting
from lighting.objects import analysis as analysis_mod
from lighting.objects import light_scene
from lighting.objects import luminaire as luminaire_mod
from lighting.objects import results as results_obj
from lighting.solver import store
from wbtest import DocTestCase, build_office, needs_solver, work_dir

WINDOW_ROW = ("Luminaire01", "Luminaire02")
#: k sigma for comparing two independent estimates (k >= 4: not flaky, not vacuous).
K_SIGMA = 4.0
Z95 = 1.959963984540054


def _group_office(photons: int = 100_000):
    """The office with its luminaires in two control groups: the window row and the rest."""
    doc = build_office(photons=photons)
    for name in WINDOW_ROW:
        doc.getObject(name).ControlGroup = "Window row"
    for name in ("Luminaire03", "Luminaire04"):
        doc.getObject(name).ControlGroup = "Back row"
    analysis = doc.getObject("LightingAnalysis")
    analysis.Decide = False  # exactly the photons asked for: comparable runs
    doc.recompute()
    return doc, analysis


def _entry(data, name):
    return next(t for t in data["targets"] if t["name"] == name)


class ControlGroups(DocTestCase):
    def test_groups_default_to_the_luminaire_and_are_exported(self):
        doc = build_office()
        analysis = doc.getObject("LightingAnalysis")
        self.assertEqual(analysis_mod.control_groups(analysis),
                         ["Luminaire01", "Luminaire02", "Luminaire03", "Luminaire04"])
        lum = doc.getObject("Luminaire01")
        self.assertEqual(luminaire_mod.scene_entry(lum)["group"], "Luminaire01")
        lum.ControlGroup = "  Window row "
        self.assertEqual(luminaire_mod.scene_entry(lum)["group"], "Window row")

    def test_layout_members_share_the_layout_group(self):
        doc = build_office()
        analysis = doc.getObject("LightingAnalysis")
        layout = lighting.add_luminaire_layout(doc, template=doc.getObject("Luminaire04"),
                                               rows=2, columns=2, area_m=(2.0, 2.0),
                                               analysis=analysis)
        doc.recompute()
        groups = analysis_mod.control_groups(analysis)
        self.assertIn(layout.Name, groups)
        self.assertNotIn("Luminaire04", groups)  # a template is not placed

    def test_contributions_are_exported_and_fingerprinted(self):
        doc, analysis = _group_office()
        self.assertNotIn("contributions", analysis_mod.settings(analysis))
        lighting.make_light_scene(analysis, "Evening")
        self.assertTrue(analysis.Contributions)
        self.assertTrue(analysis_mod.settings(analysis)["contributions"])

    def test_light_scenes_are_exported_for_the_report(self):
        """The scene's metadata.light_scenes (docs/scene-format.md, Metadata): each light
        scene's levels, which the report shows rescaled; a scene whose levels do not pair up
        is left out (Check names it)."""
        doc, analysis = _group_office()
        lighting.make_light_scene(analysis, "Evening", {"Back row": 0.5})
        broken = lighting.make_light_scene(analysis, "Broken")
        broken.Levels = [1.0]
        from lighting.export.scene import build_scene

        scene = build_scene(analysis).scene
        self.assertEqual(scene["metadata"]["light_scenes"],
                         [{"name": "Evening", "levels": {"Window row": 1.0, "Back row": 0.5}}])


class LightScenes(DocTestCase):
    def test_a_new_scene_has_every_group_at_full_and_is_shown(self):
        doc, analysis = _group_office()
        scene = lighting.make_light_scene(analysis, "Evening", {"Back row": 0.5})
        self.assertIs(analysis.ActiveLightScene, scene)
        self.assertEqual(light_scene.levels(scene), {"Window row": 1.0, "Back row": 0.5})
        self.assertEqual(light_scene.describe(scene, light_scene.levels(scene)),
                         "Evening: Back row 50 %")
        lighting.show_light_scene(analysis, None)
        self.assertIsNone(analysis.ActiveLightScene)
        lighting.show_light_scene(analysis, "Evening")
        self.assertIs(analysis.ActiveLightScene, scene)
        with self.assertRaisesRegex(ValueError, "no light scene 'Night'"):
            lighting.show_light_scene(analysis, "Night")

    def test_bad_levels_are_named(self):
        doc, analysis = _group_office()
        scene = lighting.make_light_scene(analysis, "Broken")
        scene.Levels = [1.0]
        problems = light_scene.check(scene, analysis_mod.control_groups(analysis))
        self.assertEqual(problems[0][0], "error")
        self.assertIn("2 groups but 1 levels", problems[0][1])
        scene.Levels = [1.0, -0.5]
        self.assertIn("level of group 'Back row' must be a number >= 0",
                      light_scene.check(scene, ["Window row", "Back row"])[0][1])
        scene.Levels = [1.0, float("nan")]
        self.assertEqual(light_scene.check(scene, ["Window row", "Back row"])[0][0], "error")
        scene.Groups = ["Window row", "Corridor"]
        scene.Levels = [1.0, 0.0]
        problems = light_scene.check(scene, ["Window row", "Back row"])
        self.assertEqual(problems[0], ("warning", "Light scene 'Broken': no luminaire is in "
                                                  "group(s) Corridor"))
        # Back row is a group the scene no longer sets: at 100 %, said, not silent.
        self.assertEqual(len(problems), 2)
        self.assertIn("does not set group(s) Back row", problems[1][1])
        report = lighting.check(doc, analysis, need_solver=False)
        self.assertTrue(any("Corridor" in m.text for m in report.messages))

    def test_a_group_made_after_the_scene_is_named(self):
        """A luminaire added after the scene, in a new group, is at 100 % in that scene: Check
        says so instead of letting it pass silently (issue 25)."""
        doc, analysis = _group_office()
        scene = lighting.make_light_scene(analysis, "Evening", {"Back row": 0.0})
        self.assertEqual(light_scene.check(scene, analysis_mod.control_groups(analysis)), [])
        lamp = lighting.make_luminaire(doc, (1.0, 1.0, 2.9), name="DeskLamp", analysis=analysis)
        lamp.ControlGroup = "Desk lamp"
        doc.recompute()
        problems = light_scene.check(scene, analysis_mod.control_groups(analysis))
        self.assertEqual(len(problems), 1, problems)
        self.assertEqual(problems[0][0], "warning")
        self.assertIn("'Evening' does not set group(s) Desk lamp", problems[0][1])
        self.assertIn("100 %", problems[0][1])


class RescaledResults(DocTestCase):
    @needs_solver
    def test_switching_and_dimming_rescale_one_run(self):
        import lightsolver

        doc, analysis = _group_office()
        scene = lighting.make_light_scene(analysis, "Evening",
                                          {"Window row": 0.5, "Back row": 0.0})
        lighting.show_light_scene(analysis, None)
        result = lighting.analyze(doc, output_dir=work_dir("scenes"))
        obj = results_obj.of_analysis(analysis)
        traced = results_obj.traced(obj)
        self.assertEqual([g["name"] for g in traced["groups"]], ["Window row", "Back row"])
        stored_json, photons = obj.ResultsJson, obj.Photons
        as_traced = _entry(traced, "Workplane")["mean_lux"]
        self.assertAlmostEqual(result["Workplane"].mean_lux, as_traced, 9)

        lighting.show_light_scene(analysis, scene)  # no tracing: the stored run is kept
        self.assertEqual(obj.ResultsJson, stored_json)
        self.assertEqual(obj.Photons, photons)
        self.assertEqual(obj.LightScene, "Evening: Window row 50 %, Back row off")
        shown = results_obj.data(obj)
        expected = lightsolver.rescale(traced, {"Window row": 0.5, "Back row": 0.0})
        self.assertEqual(_entry(shown, "Workplane")["mean_lux"],
                         _entry(expected, "Workplane")["mean_lux"])
        contributions = _entry(traced, "Workplane")["contributions"]
        self.assertAlmostEqual(_entry(shown, "Workplane")["mean_lux"],
                               0.5 * contributions["Window row"]["illuminance_lux"], 6)
        self.assertAlmostEqual(results_obj.mean_lux(obj, "Workplane"),
                               _entry(shown, "Workplane")["mean_lux"], 9)
        loaded = store.load_from_document(analysis)
        self.assertAlmostEqual(loaded["Workplane"].mean_lux,
                               _entry(shown, "Workplane")["mean_lux"], 9)
        self.assertEqual(store.results_state(analysis).state, "current")

        # A level change re-derives at once, as one undo step.
        doc.UndoMode = 1  # headless documents record no undo steps by default
        doc.openTransaction("Light scene level")
        scene.Levels = [1.0, 1.0]
        doc.commitTransaction()
        self.assertAlmostEqual(results_obj.mean_lux(obj, "Workplane"), as_traced,
                               delta=1e-9 * as_traced)
        doc.undo()
        self.assertEqual(list(scene.Levels), [0.5, 0.0])
        self.assertAlmostEqual(results_obj.mean_lux(obj, "Workplane"),
                               _entry(shown, "Workplane")["mean_lux"], 9)

    @needs_solver
    def test_a_dimmed_scene_agrees_with_a_run_traced_dimmed(self):
        doc, analysis = _group_office(photons=200_000)
        lighting.make_light_scene(analysis, "Dimmed", {"Window row": 0.25})
        lighting.analyze(doc, output_dir=work_dir("scenes_rescaled"))
        shown = _entry(results_obj.data(results_obj.of_analysis(analysis)), "Workplane")
        # The same dimming traced: the window row's flux times 0.25, another seed.
        for name in WINDOW_ROW:
            doc.getObject(name).FluxLumen = 0.25 * float(doc.getObject(name).FluxLumen)
        analysis.Seed = 7
        lighting.show_light_scene(analysis, None)
        traced = lighting.analyze(doc, output_dir=work_dir("scenes_traced"))["Workplane"]
        sigma = math.hypot((shown["ci_high_lux"] - shown["ci_low_lux"]) / (2 * Z95),
                           (traced.ci_high_lux - traced.ci_low_lux) / (2 * Z95))
        self.assertGreater(sigma, 0.0)
        self.assertLess(abs(shown["mean_lux"] - traced.mean_lux), K_SIGMA * sigma)
        self.assertLess(shown["ci_low_lux"], shown["mean_lux"])

    @needs_solver
    def test_an_analysis_with_an_observer_grid_shows_its_light_scenes(self):
        """Observer grids are rescaled too (docs/glare.md, "Rescaling an observer grid"): the
        scene is shown, with every eye's L_b and UGR those of lightsolver.rescale."""
        import lightsolver

        doc, analysis = _group_office(photons=50_000)
        eye = lighting.make_observer(doc, (1.0, 1.0, 1.2), ugr_max=19.0, name="EyeGrid",
                                     analysis=analysis)
        eye.GridMode, eye.GridLength, eye.GridWidth = True, 3000.0, 2000.0
        scene = lighting.make_light_scene(analysis, "Evening", {"Back row": 0.5})
        lighting.show_light_scene(analysis, None)
        lighting.analyze(doc, output_dir=work_dir("scenes_glare"))
        obj = results_obj.of_analysis(analysis)
        traced = _entry(results_obj.traced(obj), "EyeGrid")
        self.assertIn("glare_terms", traced["observer_grid"])
        lighting.show_light_scene(analysis, scene)
        self.assertEqual(obj.LightScene, "Evening: Back row 50 %")
        shown = _entry(results_obj.data(obj), "EyeGrid")
        expected = _entry(lightsolver.rescale(results_obj.traced(obj),
                                              {"Window row": 1.0, "Back row": 0.5}), "EyeGrid")
        for key in ("ugr", "background_luminance_cd_m2"):
            self.assertEqual(shown["observer_grid"][key], expected["observer_grid"][key])
        # Dimming the back row lowers the eyes' background luminance: none rises, and some
        # fall (an eye that no back-row photon reached at 5e4 photons keeps its value).
        pairs = [(lb, traced_lb) for row, traced_row in
                 zip(shown["observer_grid"]["background_luminance_cd_m2"],
                     traced["observer_grid"]["background_luminance_cd_m2"])
                 for lb, traced_lb in zip(row, traced_row)]
        self.assertTrue(all(lb <= traced_lb for lb, traced_lb in pairs))
        self.assertTrue(any(lb < traced_lb for lb, traced_lb in pairs))

    @needs_solver
    def test_a_scene_needs_a_run_with_contributions(self):
        doc, analysis = _group_office(photons=20_000)
        lighting.analyze(doc, output_dir=work_dir("scenes_plain"))
        obj = results_obj.of_analysis(analysis)
        before = results_obj.mean_lux(obj, "Workplane")
        lighting.make_light_scene(analysis, "Late", {"Back row": 0.0})
        self.assertIn("traced without contributions; run again", obj.LightScene)
        self.assertEqual(results_obj.mean_lux(obj, "Workplane"), before)
        self.assertEqual(store.results_state(analysis).state, "stale")  # Contributions on


if __name__ == "__main__":
    unittest.main()
