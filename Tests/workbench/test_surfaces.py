"""Calculation surfaces on walls and ceilings: grids on any planar face (geometry, export,
requirement presets), their analysed cells, iso-lux levels and the plan-view PNG."""
import json
import math
import os
import unittest

import FreeCAD

import lighting
from lighting import isolux, plots, standards
from lighting.objects import target as target_mod
from wbtest import DocTestCase, build_office, needs_solver, work_dir

V = FreeCAD.Vector
OFFICE_ACTIVITY = "Offices: Writing, typing, reading, data processing"


def office_with_surface_grids(photons: int = 100000):
    """The example office plus a grid on the north wall's inner face and one on the ceiling's
    underside (its 0.2 m over the walls left out by the border band)."""
    import office_model

    doc = build_office(photons=photons)
    objects = office_model.OBJECTS
    analysis = doc.getObject(objects["analysis"])
    walls, ceiling = doc.getObject(objects["walls"]), doc.getObject(objects["ceiling"])
    ceiling_face = office_model.find_face(ceiling.Shape, V(0, 0, -1), V(0, 0, 3000))
    wall = lighting.make_grid_target(doc, walls, face=objects["wall_face"], surface="Wall",
                                     activity=OFFICE_ACTIVITY, name="NorthWallGrid",
                                     analysis=analysis)
    top = lighting.make_grid_target(doc, ceiling, face=ceiling_face, surface="Ceiling",
                                    wall_band_m=0.2, activity=OFFICE_ACTIVITY,
                                    name="CeilingGrid", analysis=analysis)
    doc.recompute()
    return doc, wall, top


def _close(a, b, tol=1e-6):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


class SurfaceRules(unittest.TestCase):
    def test_presets(self):
        self.assertEqual(standards.requirement(standards.GENERAL, "Wall"), (75.0, 0.10))
        self.assertEqual(standards.requirement(standards.GENERAL, "Ceiling"), (50.0, 0.10))
        self.assertEqual(standards.requirement(OFFICE_ACTIVITY, "Wall"), (150.0, 0.10))
        self.assertEqual(standards.requirement(OFFICE_ACTIVITY, "Ceiling"), (100.0, 0.10))
        self.assertEqual(standards.requirement(OFFICE_ACTIVITY, "Work plane"), (500.0, 0.60))
        self.assertIsNone(standards.requirement("Custom", "Wall"))
        with self.assertRaisesRegex(ValueError, "unknown activity"):
            standards.requirement("Disco", "Wall")

    def test_kind_from_normal(self):
        self.assertEqual(standards.surface_kind(1.0), "Work plane")
        self.assertEqual(standards.surface_kind(-1.0), "Ceiling")
        self.assertEqual(standards.surface_kind(0.0), "Wall")
        self.assertEqual(standards.surface_kind(0.5), "Wall")  # a steep roof light's reveal

    def test_caption_verdicts(self):
        import numpy as np

        data = plots.GridPlot("W", "Wall", (5.0, 3.0), np.full((2, 2), 100.0), mean_lux=100.0,
                              min_lux=5.0, max_lux=200.0, uniformity=0.05, required_lux=75.0,
                              required_uniformity=0.1, verdicts={"em": "pass", "u0": "fail"},
                              estimated=True)
        self.assertIn("Em 100 lx", data.caption())
        # The reader's estimates (results without the solver's verdicts), said to be ones.
        self.assertIn("Em \u2265 75 lx (met (estimate))", data.caption())
        self.assertIn("U0 \u2265 0.1 (NOT met (estimate))", data.caption())
        # The solver's: the verdict from the interval.
        data.verdicts, data.estimated = {"em": "undecided", "u0": "pass"}, False
        self.assertIn("Em \u2265 75 lx (undecided)", data.caption())
        self.assertIn("U0 \u2265 0.1 (pass)", data.caption())
        data.verdicts = {"em": "fail"}
        self.assertIn("Em \u2265 75 lx (FAIL)", data.caption())
        self.assertIn("U0 \u2265 0.1 (not judged)", data.caption())

    def test_nice_levels(self):
        self.assertEqual(isolux.nice_levels(80.0, 260.0), [100.0, 150.0, 200.0, 250.0])
        self.assertEqual(isolux.nice_levels(5.0, 5.0), [])


class SurfaceGrids(DocTestCase):
    def test_wall_grid_geometry_and_export(self):
        doc, wall, _ = office_with_surface_grids()
        rect = target_mod.grid_rectangle(wall)
        # The north wall's inner face is the plane y = 4 m; the grid lies 10 mm in front of it,
        # over the whole face (x 0..5 m, z 0..3 m), facing the room (-y).
        self.assertEqual(wall.Surface, "Wall")
        self.assertAlmostEqual(float(wall.Offset), 10.0)
        self.assertAlmostEqual(float(wall.WallBand), 0.0)
        self.assertTrue(_close(rect.normal, (0, -1, 0)))
        for point in (rect.corner, rect.corner + rect.edge1, rect.corner + rect.edge2):
            self.assertAlmostEqual(point.y, 4000.0 - 10.0, 6)
        self.assertTrue(_close(rect.corner, (0, 3990, 0), 1e-6))
        self.assertTrue(_close(rect.edge1, (5000, 0, 0), 1e-6))
        self.assertTrue(_close(rect.edge2, (0, 0, 3000), 1e-6))
        # EN 12464-1 spacing from the longer side (5 m -> 0.616 m): 9 x 5 cells.
        self.assertEqual((rect.nu, rect.nv), (9, 5))
        self.assertEqual((wall.CellsU, wall.CellsV), (9, 5))
        self.assertEqual(len(wall.Shape.Faces), 45)
        self.assertEqual((wall.RequiredLux, wall.RequiredUniformity), (150.0, 0.10))
        scene_file = lighting.export_scene(doc, directory=work_dir("surfaces-export"))
        with open(scene_file, encoding="utf-8") as stream:
            scene = json.load(stream)
        entry = next(t for t in scene["targets"] if t["name"] == "NorthWallGrid")
        self.assertEqual(entry["type"], "grid")
        self.assertTrue(_close(entry["corner"], (0.0, 3.99, 0.0)))
        self.assertTrue(_close(entry["edge1"], (5.0, 0.0, 0.0)))
        self.assertTrue(_close(entry["edge2"], (0.0, 0.0, 3.0)))
        self.assertEqual(entry["cells"], [9, 5])
        e1, e2 = V(*entry["edge1"]), V(*entry["edge2"])
        normal = e1.cross(e2).normalize()  # the side the solver counts
        self.assertTrue(_close(normal, (0, -1, 0)))

    def test_ceiling_grid_faces_down(self):
        doc, _, top = office_with_surface_grids()
        rect = target_mod.grid_rectangle(top)
        self.assertTrue(_close(rect.normal, (0, 0, -1)))
        for point in (rect.corner, rect.corner + rect.edge1, rect.corner + rect.edge2):
            self.assertAlmostEqual(point.z, 3000.0 - 10.0, 6)
        # The slab's underside runs 0.2 m over the walls; the band leaves the room's 5 x 4 m.
        self.assertAlmostEqual(rect.edge1.Length, 5000.0, 6)
        self.assertAlmostEqual(rect.edge2.Length, 4000.0, 6)
        self.assertEqual((rect.nu, rect.nv), (9, 7))
        self.assertEqual((top.RequiredLux, top.RequiredUniformity), (100.0, 0.10))
        self.assertEqual(target_mod.check(top), [])

    def test_space_face_grid_faces_inward(self):
        import office_model

        doc = build_office()
        space = doc.getObject(office_model.OBJECTS["space"])
        # The space's east face: outward normal +x at x = 5 m; a grid on it faces the room.
        face = office_model.find_face(space.Shape, V(1, 0, 0), V(5000, 0, 0))
        grid = lighting.make_grid_target(doc, space, face=face, surface="Wall", offset_m=0.0)
        doc.recompute()
        rect = target_mod.grid_rectangle(grid)
        self.assertTrue(_close(rect.normal, (-1, 0, 0)))
        self.assertAlmostEqual(rect.corner.x, 5000.0, 6)

    def test_floor_grids(self):
        import office_model

        doc = build_office()
        space = doc.getObject(office_model.OBJECTS["space"])
        floor = doc.getObject(office_model.OBJECTS["floor"])
        # Without a face: horizontal, Offset above the floor level, the 0.5 m wall band.
        plain = lighting.make_grid_target(doc, space, surface="Floor", name="FloorGrid",
                                          activity="Traffic zones inside buildings: Circulation areas and corridors")
        top = office_model.find_face(floor.Shape, V(0, 0, 1), V(0, 0, 0))
        on_face = lighting.make_grid_target(doc, floor, face=top, surface="Floor",
                                            wall_band_m=0.7, name="FloorFaceGrid")
        doc.recompute()
        rect = target_mod.grid_rectangle(plain)
        self.assertTrue(_close(rect.normal, (0, 0, 1)))
        self.assertTrue(_close(rect.corner, (500, 500, 10)))
        self.assertTrue(_close(rect.edge1 + rect.edge2, (4000, 3000, 0)))
        self.assertEqual((plain.RequiredLux, plain.RequiredUniformity), (100.0, 0.40))
        # On the slab's top face (5.4 x 4.4 m, under the walls too) less a 0.7 m band.
        rect = target_mod.grid_rectangle(on_face)
        self.assertTrue(_close(rect.normal, (0, 0, 1)))
        self.assertTrue(_close(rect.corner, (500, 500, 10)))
        self.assertTrue(_close(rect.edge1 + rect.edge2, (4000, 3000, 0)))

    def test_presets_follow_kind_and_typing_makes_custom(self):
        doc, wall, _ = office_with_surface_grids()
        wall.Surface = "Ceiling"
        self.assertEqual(wall.RequiredLux, 100.0)
        wall.Activity = standards.GENERAL
        self.assertEqual((wall.RequiredLux, wall.RequiredUniformity), (50.0, 0.10))
        wall.RequiredLux = 120.0  # typed by hand
        self.assertEqual(wall.Activity, "Custom")
        self.assertEqual(wall.RequiredLux, 120.0)
        wall.Surface = "Wall"  # Custom: the typed values stay
        self.assertEqual((wall.RequiredLux, wall.RequiredUniformity), (120.0, 0.10))

    def test_bad_surface_grids_are_named(self):
        doc = FreeCAD.newDocument("BadSurfaces")
        cylinder = doc.addObject("Part::Cylinder", "Column")
        doc.recompute()
        # A curved face is refused before anything is made (issue 25) ...
        with self.assertRaisesRegex(ValueError, "'Column.Face1' is curved"):
            lighting.make_grid_target(doc, cylinder, face="Face1", surface="Wall",
                                      name="CurvedGrid")
        self.assertIsNone(doc.getObject("CurvedGrid"))
        # ... and a grid whose face is changed to a curved one later is named by its check.
        curved = lighting.make_grid_target(doc, cylinder, face="Face2", surface="Wall",
                                           name="CurvedGrid")
        curved.Base = (cylinder, ["Face1"])
        whole = lighting.make_grid_target(doc, cylinder, surface="Ceiling", name="NoFaceGrid")
        doc.recompute()
        self.assertRegex(target_mod.check(curved)[0][1], "CurvedGrid.*not planar")
        self.assertRegex(target_mod.check(whole)[0][1], "NoFaceGrid.*select one planar face")
        with self.assertRaisesRegex(ValueError, "surface must be one of"):
            lighting.make_grid_target(doc, cylinder, surface="Roof")

    def test_presets_survive_save_and_reopen(self):
        doc, wall, top = office_with_surface_grids()
        wall.RequiredLux = 180.0
        path = os.path.join(work_dir("surfaces-save"), "office.FCStd")
        doc.saveAs(path)
        FreeCAD.closeDocument(doc.Name)
        doc = FreeCAD.openDocument(path)
        wall, top = doc.getObject("NorthWallGrid"), doc.getObject("CeilingGrid")
        self.assertEqual((wall.Activity, wall.RequiredLux), ("Custom", 180.0))
        self.assertEqual((top.Activity, top.RequiredLux), (OFFICE_ACTIVITY, 100.0))
        self.assertEqual(top.Surface, "Ceiling")


class AnalysedSurfaces(DocTestCase):
    @classmethod
    def setUpClass(cls):
        cls.result = None

    def analysed(self):
        doc, wall, top = office_with_surface_grids(photons=100000)
        result = lighting.analyze(doc, output_dir=work_dir("surfaces-run"))
        return doc, wall, top, result

    @needs_solver
    def test_cells_finite_in_their_intervals_and_plots(self):
        doc, wall, top, result = self.analysed()
        for name in ("NorthWallGrid", "CeilingGrid"):
            grid = result[name]
            self.assertEqual(grid.kind, "grid")
            nu, nv = grid.cells_uv
            self.assertEqual(len(grid.cells_lux), nu * nv)
            for lux, low, high in zip(grid.cells_lux, grid.cells_ci_low_lux,
                                      grid.cells_ci_high_lux):
                self.assertTrue(math.isfinite(lux) and math.isfinite(low) and math.isfinite(high))
                self.assertLessEqual(low, lux)
                self.assertLessEqual(lux, high)
            self.assertGreater(min(grid.cells_lux), 0.0, f"{name}: a cell got no light")
        # The wall grid 10 mm in front of the north wall sees what the face target on that
        # wall sees: their means agree within their intervals (plus the grid's edge effect).
        grid, face = result["NorthWallGrid"], result["NorthWall"]
        slack = (grid.ci_high_lux - grid.ci_low_lux) + (face.ci_high_lux - face.ci_low_lux)
        self.assertLess(abs(grid.mean_lux - face.mean_lux), slack,
                        f"wall grid {grid.mean_lux:.1f} lx vs face target {face.mean_lux:.1f} lx")
        # The ceiling is lit only by reflected light: far less than the work plane.
        self.assertLess(result["CeilingGrid"].mean_lux, result["Workplane"].mean_lux)
        self._check_isolux(doc, wall)
        self._check_png(doc, wall)
        self._check_png(doc, doc.getObject("Workplane"))

    def _check_isolux(self, doc, wall):
        analysis = doc.getObject("LightingAnalysis")
        data = plots.grid_plot_data(analysis, wall)
        scale = plots.analysis_scale(analysis)
        levels = isolux.levels(scale, data.lux.ravel())
        self.assertGreaterEqual(len(levels), 2)
        low, high = float(data.lux.min()), float(data.lux.max())
        for level in levels:
            self.assertTrue(low < level < high, f"level {level} outside {low}..{high}")
        found = isolux.lines(data.lux, data.size_m, levels)
        self.assertTrue(found)
        lu, lv = data.size_m
        for level, points in found:
            self.assertIn(level, levels)
            self.assertTrue(((points[:, 0] >= -1e-9) & (points[:, 0] <= lu + 1e-9)).all())
            self.assertTrue(((points[:, 1] >= -1e-9) & (points[:, 1] <= lv + 1e-9)).all())

    def _check_png(self, doc, target):
        from matplotlib import image

        path = os.path.join(work_dir("surfaces-png"), f"{target.Name}.png")
        self.assertEqual(plots.save_grid_png(target, path, width_px=640), path)
        pixels = image.imread(path)
        self.assertEqual(pixels.shape[1], 640)
        self.assertGreater(pixels.shape[0], 200)
        colours = {tuple(p) for p in (pixels[::4, ::4, :3] * 255).astype(int).reshape(-1, 3)}
        self.assertGreater(len(colours), 50, "the plan view looks blank")

    def test_png_needs_results(self):
        doc, wall, _ = office_with_surface_grids()
        with self.assertRaisesRegex(ValueError, "NorthWallGrid.*no results"):
            plots.save_grid_png(wall, os.path.join(work_dir("surfaces-nores"), "x.png"))


if __name__ == "__main__":
    unittest.main()
