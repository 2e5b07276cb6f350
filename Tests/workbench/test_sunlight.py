"""EN 17037 sunlight exposure in the workbench: the Sky's switch gives each window portal a
reference point (mid-width on the wall's inner face, 1.2 m over the floor and 0.3 m over the
sill where the opening allows, normal out of the room), the scene's ``sunlight_exposure``, the
solver's hours read back and shown (docs/workbench-daylight.md, "Sunlight exposure")."""
import math

import FreeCAD

import lighting
from lighting.export import portals as portals_mod
from lighting.export import scene as scene_mod
from lighting.export import sunlight as sunlight_mod
from lighting.objects.analysis import find_analysis
from wbtest import DocTestCase, build_office, needs_solver, work_dir

V = FreeCAD.Vector


def office_with_sunlight(**options):
    """The example office (south window 1.5 x 1.2 m at x 1.75-3.25 m, z 0.9-2.1 m in the wall
    y = -0.2 ... 0, floor z = 0) with a Sky asking for sunlight exposure."""
    doc = build_office(photons=20000)
    analysis = find_analysis(doc)
    sky = lighting.make_sky(doc, analysis=analysis)
    sky.SunlightExposure = True
    for key, value in options.items():
        setattr(sky, key, value)
    doc.recompute()
    return doc, analysis, sky


def portal(corner, edge1, edge2, label="W"):
    """A wall portal from metre lists (mm inside, as find_portals gives them)."""
    mm = [V(*[c * 1000.0 for c in p]) for p in (corner, edge1, edge2)]
    return portals_mod.Portal("W", label, *mm)


class ReferencePoints(DocTestCase):
    def test_the_office_window_reference_point_and_normal(self):
        doc, analysis, sky = office_with_sunlight()
        result = scene_mod.build_scene(analysis)
        self.assertEqual(result.report.errors, [])
        entry = result.scene["sunlight_exposure"]
        self.assertEqual(entry["date"], "2026-03-21")  # 21 March of the Sky's year
        self.assertEqual(entry["min_elevation_deg"], 11.0)
        self.assertEqual(entry["step_minutes"], 1)
        self.assertEqual(entry["site"], {"latitude_deg": 48.85, "longitude_deg": 2.35,
                                         "utc_offset_h": 1.0, "elevation_m": 35.0})
        (point,) = entry["points"]
        self.assertEqual(point["name"], "Window")
        # Mid-width x 2.5, the wall's inner face y = 0, the opening's centre z 1.5 (above
        # 1.2 m over the floor and 0.3 m over the sill 0.9): out of the room is -y.
        for got, want in zip(point["position"], (2.5, 0.0, 1.5)):
            self.assertAlmostEqual(got, want, 6)
        for got, want in zip(point["normal"], (0.0, -1.0, 0.0)):
            self.assertAlmostEqual(got, want, 9)

    def test_off_by_default_and_settings_exported(self):
        doc, analysis, sky = office_with_sunlight(SunlightExposure=False)
        self.assertNotIn("sunlight_exposure", scene_mod.build_scene(analysis).scene)
        sky.SunlightExposure, sky.SunlightDate = True, "2026-02-10"
        sky.SunlightMinAltitude, sky.SunlightStepMinutes = 14.5, 5
        entry = scene_mod.build_scene(analysis).scene["sunlight_exposure"]
        self.assertEqual((entry["date"], entry["min_elevation_deg"], entry["step_minutes"]),
                         ("2026-02-10", 14.5, 5))

    def test_a_date_outside_the_span_warns_and_a_bad_one_is_an_error(self):
        doc, analysis, sky = office_with_sunlight(SunlightDate="2026-06-21")
        result = scene_mod.build_scene(analysis)
        self.assertTrue(any("1 February" in m.text for m in result.report.warnings))
        self.assertEqual(result.scene["sunlight_exposure"]["date"], "2026-06-21")
        sky.SunlightDate = "21/03/2026"
        errors = [m.text for m in scene_mod.build_scene(analysis).report.errors]
        self.assertTrue(any("SunlightDate" in e and "Sky" in e for e in errors), errors)

    def test_low_openings_raise_the_point_or_say_why_not(self):
        # Sill 0.1 m, 2 m tall: the centre 1.1 m is raised to 1.2 m over the floor.
        p = sunlight_mod.reference_point(portal((1, 0, 0.1), (0, 0, 2.0), (1.0, 0, 0)), 0.0)
        self.assertAlmostEqual(p.position.z, 1200.0, 6)
        self.assertAlmostEqual(p.position.x, 1500.0, 6)  # mid-width
        self.assertEqual(p.note, "")
        # Sill 1.0 m, 0.4 m tall: 0.3 m over the sill (1.3) beats the centre (1.2).
        p = sunlight_mod.reference_point(portal((0, 0, 1.0), (1.0, 0, 0), (0, 0, 0.4)), 0.0)
        self.assertAlmostEqual(p.position.z, 1300.0, 6)
        # Top at 1.0 m: 1.2 m over the floor is out of reach, the centre stays, said why.
        p = sunlight_mod.reference_point(portal((0, 0, 0.2), (1.0, 0, 0), (0, 0, 0.8)), 0.0)
        self.assertAlmostEqual(p.position.z, 600.0, 6)
        self.assertIn("centre height", p.note)
        # The normal is the reverse of the portal's inward normal (edge1 x edge2).
        q = portal((0, 0, 1.0), (1.0, 0, 0), (0, 0, 1.0))
        self.assertAlmostEqual((sunlight_mod.reference_point(q, 0.0).normal
                                + q.inward).Length, 0.0, 9)


class SunlightTraced(DocTestCase):
    @needs_solver
    def test_the_run_gives_the_south_windows_hours_as_the_solver_computes_them(self):
        import lightsolver

        doc, analysis, sky = office_with_sunlight()
        for lum in lighting.objects.luminaire_layout.placed_luminaires(analysis):
            lum.FluxLumen = 0.0  # daylight only
        analysis.Photons = 20000
        doc.recompute()
        path = lighting.export_scene(doc, directory=work_dir("sunlight-export"))
        direct = lightsolver.sunlight_exposure(path)
        result = lighting.analyze(doc, output_dir=work_dir("sunlight-run"))
        view = result.sunlight
        self.assertIsNotNone(view)
        self.assertEqual(view.date, "2026-03-21")
        (point,) = view.points
        (want,) = direct["points"]
        self.assertEqual(point.name, "Window")
        self.assertEqual(point.hours, want["hours"])
        self.assertEqual(point.level, want["level"])
        # 21 March in Paris: the sun is above 11 degrees for about 9 h and passes the south
        # window's reveals for most of them: hours, never the whole day.
        self.assertTrue(1.5 < point.hours < 12.0 and math.isfinite(point.hours), point.hours)
        minutes = int(round(point.hours * 60))
        line = f"Window: {minutes // 60} h {minutes % 60:02d} min, {point.level}"
        text = result.table()
        print("\n" + text)
        self.assertIn(line, text)
        self.assertIn("Sunlight exposure (EN 17037), 2026-03-21, sun above 11°:", text)
        from lighting.solver import results as results_mod
        self.assertEqual(results_mod.sunlight_lines(view)[1], line)


class TableHeader(DocTestCase):
    def test_the_value_header_names_what_its_rows_hold(self):
        from types import SimpleNamespace

        from lighting.solver import results as results_mod

        def result(*kinds):
            return SimpleNamespace(targets=[SimpleNamespace(
                is_glare=k == "ugr", daylight_factor=object() if k == "df" else None)
                for k in kinds])

        header = results_mod.value_header
        self.assertEqual(header(result("lux", "lux")), "Em lx")
        self.assertEqual(header(result("lux", "df")), "Em lx / DF %")  # text: DF grids' lux too
        self.assertEqual(header(result("df"), grid_lux=False), "DF %")  # the panel's DF row
        self.assertEqual(header(result("lux", "df", "ugr"), grid_lux=False), "Em lx / DF % / UGR")
        self.assertEqual(results_mod.sunlight_lines(None), [])
