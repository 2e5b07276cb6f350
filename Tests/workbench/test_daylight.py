"""Daylight in the workbench: a Sky's portals from Arch windows (the wall's inner face, the
room's side, the window left out), its glazing, site and sun, and daylight-factor grids'
export (docs/scene-format.md, "Targets" and 5)."""
import json
import math

import FreeCAD

import lighting
from lighting.export import portals as portals_mod
from lighting.export import scene as scene_mod
from lighting.objects.analysis import find_analysis
from wbtest import DocTestCase, build_office, load_scene, needs_solver, work_dir

V = FreeCAD.Vector


def office_with_sky(**options):
    """The example office (south window 1.5 x 1.2 m at x 1.75-3.25 m, z 0.9-2.1 m in the
    wall y = -0.2 ... 0) with a Sky in its analysis."""
    import office_model

    doc = build_office(photons=20000)
    analysis = find_analysis(doc)
    sky = lighting.make_sky(doc, analysis=analysis, **options)
    doc.recompute()
    return doc, analysis, sky, dict(office_model.OBJECTS)


def sky_of(scene):
    return next(lum for lum in scene["luminaires"] if lum["type"] == "sky")


class WindowPortals(DocTestCase):
    def assert_office_portal(self, portal):
        """The window's opening on the wall's inner face y = 0, edge1 x edge2 along +y."""
        corner, e1, e2 = (V(*portal[k]) for k in ("corner", "edge1", "edge2"))
        inward = e1.cross(e2)
        self.assertAlmostEqual(inward.Length, 1.5 * 1.2, 9)  # the opening's area, m2
        self.assertAlmostEqual(inward.normalize().y, 1.0, 9)  # into the room (y > 0)
        xs = [corner.x, (corner + e1).x, (corner + e2).x, (corner + e1 + e2).x]
        zs = [corner.z, (corner + e1).z, (corner + e2).z, (corner + e1 + e2).z]
        self.assertAlmostEqual(min(xs), 1.75, 9)
        self.assertAlmostEqual(max(xs), 3.25, 9)
        self.assertAlmostEqual(min(zs), 0.9, 9)
        self.assertAlmostEqual(max(zs), 2.1, 9)
        for p in (corner, corner + e1, corner + e2):
            self.assertAlmostEqual(p.y, 0.0, 9)  # the wall's inner face, not its outer one

    def test_the_office_window_becomes_a_portal_and_leaves_the_scene(self):
        doc, analysis, sky, names = office_with_sky()
        self.assertEqual(sky.PortalCount, 1)
        self.assertFalse(sky.Shape.isNull())  # the portal is drawn
        result = scene_mod.build_scene(analysis)
        scene = result.scene
        entry = sky_of(scene)
        self.assertEqual(entry["model"], "cie_overcast")
        self.assertEqual(entry["diffuse_horizontal_lx"], 10000.0)
        self.assertEqual(entry["ground_reflectance"], 0.2)
        self.assertEqual(entry["group"], sky.Name)  # a group of its own (DF counts only it)
        self.assertEqual(len(entry["portals"]), 1)
        self.assert_office_portal(entry["portals"][0])
        self.assertEqual(entry["portals"][0]["glazing"], {"transmittance": 0.75, "panes": 2,
                                                          "frame_factor": 0.8,
                                                          "maintenance_factor": 0.9})
        # The window (glass and frame) is no mesh any more, and no glass material is left.
        meshes = [m["name"] for m in scene["meshes"]]
        self.assertFalse([m for m in meshes if m.split(".")[0] == names["window"]], meshes)
        self.assertFalse([k for k, m in scene["materials"].items() if m["type"] == "glass"])
        self.assertTrue(any("portal of sky" in m.text for m in result.report.messages))
        self.assertEqual(scene["metadata"]["labels"][sky.Name], sky.Label)

    def test_without_a_sky_the_window_and_its_glass_stay(self):
        import office_model

        doc = build_office(photons=20000)
        scene = scene_mod.build_scene(find_analysis(doc)).scene
        window = office_model.OBJECTS["window"]
        self.assertIn(f"{window}.default_glass", [m["name"] for m in scene["meshes"]])
        self.assertNotIn("north_deg", scene["metadata"])

    def test_a_window_facing_into_the_room_gives_the_same_portal(self):
        # Turned so that its normal points into the room (+y) instead of out of it: the
        # room's side comes from the targets, not from the window's orientation.
        doc, analysis, sky, names = office_with_sky()
        window = doc.getObject(names["window"])
        window.Placement = FreeCAD.Placement(V(1750.0, -50.0, 2100.0),
                                             FreeCAD.Rotation(V(1, 0, 0), -90))
        doc.recompute()
        found = portals_mod.find_portals(sky)
        self.assertEqual(found.problems, [])
        n = found.portals[0].inward
        self.assertAlmostEqual(n.y, 1.0, 9)
        self.assert_office_portal(sky_of(scene_mod.build_scene(analysis).scene)["portals"][0])

    def test_the_room_side_without_targets_is_the_walls_centre(self):
        doc, analysis, sky, names = office_with_sky()
        window, walls = doc.getObject(names["window"]), doc.getObject(names["walls"])
        portal = portals_mod.window_portal(window, inside=[])
        self.assertAlmostEqual(portal.inward.y, 1.0, 9)
        self.assertAlmostEqual(portal.corner.y, 0.0, 6)
        # A point outside (south of the wall) as the only target turns it outward: the rule
        # really follows the targets.
        outside = portals_mod.window_portal(window, inside=[V(2500, -3000, 1000)])
        self.assertAlmostEqual(outside.inward.y, -1.0, 9)
        self.assertAlmostEqual(outside.corner.y, -200.0, 6)  # the wall's other face
        self.assertIn(walls, window.Hosts)

    def test_a_changed_sky_or_window_changes_the_fingerprint(self):
        from lighting.export import fingerprint

        doc, analysis, sky, names = office_with_sky()
        before = fingerprint.of_analysis(analysis)
        sky.DiffuseHorizontalLux = 20000.0
        doc.recompute()
        after = fingerprint.of_analysis(analysis)
        self.assertEqual(fingerprint.differences(before, after, doc), ["sky 'Sky' changed"])
        window = doc.getObject(names["window"])
        placement = window.Placement
        placement.Base = placement.Base + V(500, 0, 0)
        window.Placement = placement
        doc.recompute()
        moved = fingerprint.differences(after, fingerprint.of_analysis(analysis), doc)
        self.assertIn("sky 'Sky' changed", moved)  # its portal (drawn) moved with the window
        portal = portals_mod.find_portals(sky).portals[0]
        self.assertAlmostEqual(sky.Shape.BoundBox.XMin, min(portal.corner.x,
                                                             (portal.corner + portal.edge1).x), 6)

    def test_the_summary_says_what_the_sky_exports(self):
        from lighting.export import daylight

        doc, analysis, sky, names = office_with_sky()
        lines = daylight.summary_lines(sky)
        print("\n" + "\n".join(lines))
        self.assertTrue(lines[0].startswith("Sky: CIE overcast, 10000 lx"))
        self.assertIn("entered values", lines[1])
        self.assertTrue(any(line.startswith("Portal 'Window': 1.50 x 1.20 m") and
                            "tau_v 0.75" in line for line in lines), lines)
        self.assertIn("frame factor 0.8, maintenance factor 0.9", lines[-1])

    def test_glazing_from_the_window_glass_material(self):
        doc, analysis, sky, names = office_with_sky()
        window = doc.getObject(names["window"])
        window.addProperty("App::PropertyFloat", "Transmittance", "Lighting", "tau_v")
        window.Transmittance = 0.62
        glazing = sky_of(scene_mod.build_scene(analysis).scene)["portals"][0]["glazing"]
        self.assertEqual(glazing["transmittance"], 0.62)
        sky.UseWindowGlass = False
        glazing = sky_of(scene_mod.build_scene(analysis).scene)["portals"][0]["glazing"]
        self.assertEqual(glazing["transmittance"], 0.75)

    def test_a_selected_face_is_a_portal_too(self):
        import Part

        doc, analysis, sky, names = office_with_sky()
        # A 1 x 1 m skylight face in the ceiling plane (z = 3 m) over the room.
        light = doc.addObject("Part::Feature", "Skylight")
        light.Shape = Part.Face(Part.makePolygon([V(1000, 1000, 3000), V(2000, 1000, 3000),
                                                  V(2000, 2000, 3000), V(1000, 2000, 3000),
                                                  V(1000, 1000, 3000)]))
        sky.PortalFaces = [(light, ["Face1"])]
        doc.recompute()
        portals = portals_mod.find_portals(sky).portals
        self.assertEqual(len(portals), 2)
        self.assertAlmostEqual(portals[1].inward.z, -1.0, 9)  # down into the room
        self.assertAlmostEqual(portals[1].edge1.cross(portals[1].edge2).Length, 1.0e6, 3)

    def test_no_portal_is_an_error_naming_the_sky(self):
        doc, analysis, sky, names = office_with_sky()
        doc.getObject(names["window"]).Hosts = []
        doc.recompute()
        result = scene_mod.build_scene(analysis)
        errors = [m.text for m in result.report.errors]
        self.assertTrue(any("Sky 'Sky' has no portals" in e for e in errors), errors)


class SiteAndSun(DocTestCase):
    def test_an_arch_site_gives_the_site_north_and_the_sun(self):
        import Arch

        doc, analysis, sky, names = office_with_sky()
        site = Arch.makeSite()
        site.Latitude, site.Longitude, site.TimeZone = 41.98, -87.92, -6
        site.Elevation = 201000.0
        site.Declination = 30.0
        sky.SunEnabled = True
        sky.DirectNormalLux = 70000.0
        sky.Date, sky.Time = "2026-06-21", "12:30"
        doc.recompute()
        self.assertEqual(sky.SiteUsed, f"Arch Site '{site.Label}'")
        scene = scene_mod.build_scene(analysis).scene
        self.assertEqual(scene["metadata"]["north_deg"], 30.0)
        sun = next(lum for lum in scene["luminaires"] if lum["type"] == "sun")
        self.assertEqual(sun["site"], {"latitude_deg": 41.98, "longitude_deg": -87.92,
                                       "elevation_m": 201.0})
        self.assertEqual(sun["time"], "2026-06-21T12:30-06:00")
        self.assertEqual(sun["north_deg"], 30.0)
        self.assertEqual(sun["illuminance_lx"], 70000.0)
        self.assertEqual(sun["portals"], sky_of(scene)["portals"])  # the same openings
        self.assertNotEqual(sun["group"], sky_of(scene)["group"])
        self.assertEqual(sky_of(scene)["sun_direct_normal_lx"], 70000.0)

    def test_entered_site_and_a_bad_date(self):
        doc, analysis, sky, names = office_with_sky()
        sky.TimeZone = 5.5
        sky.SunEnabled = True
        self.assertEqual(sky_of(scene_mod.build_scene(analysis).scene)["ground_reflectance"],
                         0.2)
        sun = next(lum for lum in scene_mod.build_scene(analysis).scene["luminaires"]
                   if lum["type"] == "sun")
        self.assertEqual(sun["time"], "2026-03-21T12:00+05:30")
        sky.Date = "2026-13-01"
        errors = [m.text for m in scene_mod.build_scene(analysis).report.errors]
        self.assertTrue(any("Date must be YYYY-MM-DD" in e for e in errors), errors)

    @needs_solver
    def test_a_cie_sky_with_a_sun_takes_the_solvers_sun_position(self):
        import lightsolver

        doc, analysis, sky, names = office_with_sky(model="CIE standard general sky")
        sky.CieType = 12
        sky.North = 15.0
        sky.Date, sky.Time = "2026-06-21", "14:00"
        entry = sky_of(scene_mod.build_scene(analysis).scene)
        want = lightsolver.sun_position(48.85, 2.35, "2026-06-21T14:00+01:00",
                                        elevation_m=35.0, north_deg=15.0)["direction"]
        self.assertEqual(entry["cie_type"], 12)
        for got, expected in zip(entry["sun_direction"], want):
            self.assertAlmostEqual(got, expected, 10)
        sky.SkyModel = "Perez"
        entry = sky_of(scene_mod.build_scene(analysis).scene)
        self.assertEqual(entry["perez"], {"diffuse_horizontal": 15000.0,
                                          "direct_normal": 40000.0, "units": "lx",
                                          "day_of_year": 172})
        self.assertNotIn("diffuse_horizontal_lx", entry)  # the Perez sky takes its own level
        self.assertIn("sun_direction", entry)
        sky.Time = "23:00"  # night: this sky needs the sun up
        errors = [m.text for m in scene_mod.build_scene(analysis).report.errors]
        self.assertTrue(any("below the horizon" in e for e in errors), errors)

    @needs_solver
    def test_the_solver_reads_the_sky_and_light_comes_in(self):
        doc, analysis, sky, names = office_with_sky()
        for lum in lighting.objects.luminaire_layout.placed_luminaires(analysis):
            lum.FluxLumen = 0.0  # daylight only
        doc.recompute()
        analysis.Photons = 200000
        result = lighting.analyze(doc, output_dir=work_dir("daylight"))
        print("\n" + result.table())
        grid = result["Workplane"]
        # An overcast 10 000 lx sky through a 1.8 m2 window into a 20 m2 room: a few hundred
        # lux on the desk plane, none if the portal faced out of the room.
        self.assertGreater(grid.mean_lux, 50.0)
        self.assertLess(grid.mean_lux, 2000.0)


    @needs_solver
    def test_the_solver_traces_the_sun_through_the_skys_portals(self):
        """The Sky's sun (its own group) through the same window: the solver reads the sun's
        portals, the sun's flux is its direct normal illuminance across the opening, and the
        work plane gets the sky's light plus the sun's patch."""
        doc, analysis, sky, names = office_with_sky()
        for lum in lighting.objects.luminaire_layout.placed_luminaires(analysis):
            lum.FluxLumen = 0.0  # daylight only
        analysis.Photons = 200000
        doc.recompute()
        without = lighting.analyze(doc, output_dir=work_dir("daylight-nosun"))["Workplane"]
        sky.SunEnabled = True  # 21 March, noon in Paris: the sun in the south window
        doc.recompute()
        result = lighting.analyze(doc, output_dir=work_dir("daylight-sun"))
        suns = [lum for lum in result.data["luminaires"] if lum["type"] == "sun"]
        self.assertEqual(len(suns), 1)
        self.assertGreater(suns[0]["emitted_flux_lm"], 0.0)
        with_sun = result["Workplane"]
        self.assertGreater(with_sun.ci_low_lux, without.ci_high_lux)

class DaylightFactorGrids(DocTestCase):
    def test_a_daylight_factor_grid_exports_its_quantity_and_requirements(self):
        doc, analysis, sky, names = office_with_sky()
        grid = doc.getObject("Workplane")
        grid.Quantity = "Daylight factor"
        grid.DaylightLevel = "Medium"
        grid.MedianDiffuseLux = 15900.0
        entry = next(t for t in scene_mod.build_scene(analysis).scene["targets"]
                     if t["name"] == "Workplane")
        self.assertEqual(entry["quantity"], "daylight_factor")
        # The illuminance requirements the office's grid holds are not exported for it.
        self.assertEqual(entry["requirements"], {"en17037": "medium", "median_diffuse_lx": 15900.0})
        self.assertNotIn("task", entry)
        grid.DaylightFactorTargetPercent = 2.0
        grid.DaylightFactorMinimumPercent = 0.7
        entry = next(t for t in scene_mod.build_scene(analysis).scene["targets"]
                     if t["name"] == "Workplane")
        self.assertEqual(entry["requirements"]["df_target_percent"], 2.0)
        self.assertEqual(entry["requirements"]["df_minimum_percent"], 0.7)
        from lighting.objects import daylight_target

        derived = daylight_target.derived_percent(grid)
        self.assertAlmostEqual(derived["df_target_percent"], 500.0 / 15900.0 * 100.0, 12)
        self.assertAlmostEqual(derived["df_minimum_percent"], 300.0 / 15900.0 * 100.0, 12)
        grid.Quantity = "Illuminance"
        entry = next(t for t in scene_mod.build_scene(analysis).scene["targets"]
                     if t["name"] == "Workplane")
        self.assertNotIn("quantity", entry)
        self.assertEqual(entry["requirements"], {"em_lux": 500.0, "u0": 0.6})

    def test_a_daylight_factor_grid_without_a_sky_is_an_error(self):
        doc = build_office(photons=20000)
        doc.getObject("Workplane").Quantity = "Daylight factor"
        errors = [m.text for m in scene_mod.build_scene(find_analysis(doc)).report.errors]
        self.assertTrue(any("reports daylight factors but the analysis has no Sky" in e
                            for e in errors), errors)

    def test_a_saved_sky_and_daylight_grid_reopen(self):
        import os

        doc, analysis, sky, names = office_with_sky()
        grid = doc.getObject("Workplane")
        grid.Quantity = "Daylight factor"
        grid.DaylightLevel = "High"
        path = os.path.join(work_dir("daylight-save"), "daylight.FCStd")
        doc.saveAs(path)
        before = scene_mod.build_scene(analysis).scene
        sky_name = sky.Name
        FreeCAD.closeDocument(doc.Name)
        doc = FreeCAD.openDocument(path)
        analysis = find_analysis(doc)
        after = scene_mod.build_scene(analysis).scene
        self.assertEqual(sky_of(after), sky_of(before))
        self.assertEqual(next(t for t in after["targets"] if t["name"] == "Workplane"),
                         next(t for t in before["targets"] if t["name"] == "Workplane"))
        self.assertEqual(doc.getObject(sky_name).PortalCount, 1)

    def test_the_scene_file_round_trips(self):
        doc, analysis, sky, names = office_with_sky()
        path = lighting.export_scene(doc, directory=work_dir("daylight-export"))
        scene = load_scene(path)
        self.assertEqual(json.loads(json.dumps(sky_of(scene)))["portals"][0]["glazing"]["panes"],
                         2)
        self.assertTrue(math.isfinite(scene["metadata"]["north_deg"]))


class DaylightFactorTraced(DocTestCase):
    """A DF grid traced by the solver itself: its daylight factor, the EN 17037 verdicts and
    the table, read through the results reader (no hand-written result)."""

    @needs_solver
    def test_the_solver_traces_a_daylight_factor_grid_with_en17037_verdicts(self):
        from lighting import daylight_results

        doc, analysis, sky, names = office_with_sky()
        grid = doc.getObject("Workplane")
        grid.Quantity = "Daylight factor"
        grid.DaylightLevel = "Minimum"
        grid.MedianDiffuseLux = 15900.0
        doc.recompute()
        result = lighting.analyze(doc, output_dir=work_dir("daylight-traced"))
        shown = result["Workplane"]
        df = shown.daylight_factor
        self.assertIsNotNone(df)
        self.assertEqual(df.outside_illuminance_lx, 10000.0)  # the sky's level, exact
        nu, nv = shown.cells_uv
        cells = daylight_results.cells_percent(df)
        self.assertEqual(len(cells), nu * nv)
        self.assertTrue(all(math.isfinite(v) and 0.0 <= v < 100.0 for v in cells))
        for stat in (df.mean, df.min, df.p50, df.p95):
            self.assertLessEqual(stat.low, stat.value)
            self.assertLessEqual(stat.value, stat.high)
        self.assertLessEqual(df.p95.value, df.p50.value)
        lines = daylight_results.requirement_lines(shown)
        self.assertEqual(lines[0], ("EN 17037 minimum at 15900 lx", ""))
        # D_T = 300 / 15900 = 1.89 %, D_TM = 100 / 15900 = 0.63 %, each judged.
        self.assertEqual([line[0] for line in lines[1:]],
                         ["DF over 50 % of the area >= 1.89 %",
                          "DF over 95 % of the area >= 0.63 %"])
        self.assertTrue(all(line[1] in ("pass", "FAIL", "undecided") for line in lines[1:]))
        self.assertIn("DF %", result.table())


class DaylightFactorDisplay(DocTestCase):
    """The results table and colours of a DF grid, from a hand-written result in the solver's
    layout with chosen verdicts (one pass, one undecided), so every word is checked."""

    @needs_solver
    def test_a_hand_written_daylight_factor_result_is_read_and_tabled(self):
        import daylight_fixture
        from lighting import daylight_results
        from lighting.solver import store

        doc, analysis, sky, names = office_with_sky()
        result = lighting.analyze(doc, output_dir=work_dir("daylight-df"))
        grid = doc.getObject("Workplane")
        nu, nv = result["Workplane"].cells_uv
        data = daylight_fixture.add_to_results(json.loads(json.dumps(result.data)), "Workplane",
                                               sky.Name, nu, nv)
        shown = store.apply_to_document(analysis, data)
        df = shown["Workplane"].daylight_factor
        self.assertIsNotNone(df)
        self.assertIsNone(shown["Desk top"].daylight_factor)
        self.assertEqual(len(daylight_results.cells_percent(df)), nu * nv)
        table = shown.table()
        print("\n" + table)
        self.assertIn("DF %", table)
        self.assertIn(f"{df.mean.value:.2f}", table)
        figures = daylight_results.figure_lines(df)
        self.assertEqual([f[0] for f in figures], ["DF mean", "DF min", "DF over 50 %",
                                                   "DF over 95 %", "Outside (sky)"])
        self.assertEqual(figures[2][1], f"{df.p50.value:.2f} %")
        self.assertEqual(figures[2][2], f"{df.p50.low:.2f} - {df.p50.high:.2f}")
        lines = daylight_results.requirement_lines(shown["Workplane"])
        self.assertEqual(lines, [("EN 17037 medium at 15900 lx", ""),
                                 ("DF over 50 % of the area >= 3.14 %", "pass"),
                                 ("DF over 95 % of the area >= 1.89 %", "undecided")])
        from lighting.objects import results as results_obj

        stored = results_obj.data(results_obj.of_analysis(analysis))
        scale = daylight_results.scale(stored, [grid.Name, "Desk top"])
        from lighting.colormap import nice_max

        top = max(daylight_results.cells_percent(df))
        self.assertEqual((scale.min_lux, scale.max_lux), (0.0, nice_max(top)))  # %, round top
        self.assertGreaterEqual(scale.max_lux, top)
        self.assertEqual(daylight_results.overall_verdict(stored, [grid.Name]), "undecided")
