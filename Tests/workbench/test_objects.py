"""Document objects: EN 12464-1 grid rule, defaults, scene entries, undo, migration."""
import math
import os
import unittest

import FreeCAD

import lighting
from lighting import standards
from lighting.objects import luminaire as luminaire_mod
from lighting.objects import placement_domain as domain_mod
from lighting.objects import target as target_mod
from wbtest import DocTestCase, build_office, needs_solver, work_dir

V = FreeCAD.Vector


class GridRule(unittest.TestCase):
    def test_spacing_formula(self):
        # p = 0.2 * 5^log10(d): d = 5 m -> 0.616 m, d = 10 m -> 1.0 m, capped at 10 m.
        self.assertAlmostEqual(standards.grid_spacing_m(5.0), 0.2 * 5 ** math.log10(5.0), 12)
        self.assertAlmostEqual(standards.grid_spacing_m(5.0), 0.6160, 3)
        self.assertAlmostEqual(standards.grid_spacing_m(10.0), 1.0, 12)
        self.assertEqual(standards.grid_spacing_m(1e6), 10.0)
        self.assertEqual(lighting.grid_spacing_m(10.0), 1.0)

    def test_cell_counts(self):
        nu, nv, p = standards.grid_cells(4.0, 3.0)
        self.assertAlmostEqual(p, standards.grid_spacing_m(4.0), 12)
        self.assertEqual((nu, nv), (math.ceil(4.0 / p), math.ceil(3.0 / p)))
        self.assertEqual(standards.grid_cells(4.0, 3.0, 0.5)[:2], (8, 6))
        self.assertEqual(standards.grid_cells(0.1, 0.1, 1.0)[:2], (1, 1))
        with self.assertRaises(ValueError):
            standards.grid_cells(0.0, 1.0)


class Objects(DocTestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("Objects")

    def test_defaults_and_grid_over_space(self):
        doc = build_office()
        grid = doc.getObject("Workplane")
        self.assertEqual(grid.TargetType, "Grid")
        self.assertAlmostEqual(float(grid.WorkplaneHeight), 800.0)
        self.assertAlmostEqual(float(grid.WallBand), 500.0)
        self.assertAlmostEqual(float(grid.Spacing), 0.0)
        # 5 x 4 m room minus the 0.5 m band: 4 x 3 m, d = 4 m -> p = 0.527 m -> 8 x 6 cells.
        self.assertEqual((grid.CellsU, grid.CellsV), (8, 6))
        self.assertAlmostEqual(float(grid.SpacingUsed), 1000 * standards.grid_spacing_m(4.0), 6)
        rect = target_mod.grid_rectangle(grid)
        self.assertAlmostEqual(rect.corner.z, 800.0)
        self.assertEqual(len(grid.Shape.Faces), 48)
        entry = rect.scene_entry("Workplane")
        self.assertEqual(entry["corner"], [0.5, 0.5, 0.8])
        self.assertEqual(entry["edge1"], [4.0, 0.0, 0.0])
        self.assertEqual(entry["edge2"], [0.0, 3.0, 0.0])
        self.assertEqual(entry["cells"], [8, 6])
        grid.Spacing = 1000.0
        doc.recompute()
        self.assertEqual((grid.CellsU, grid.CellsV), (4, 3))

    def test_grid_over_slab_top(self):
        box = self.doc.addObject("Part::Box", "Slab")
        box.Length, box.Width, box.Height = 6000, 3000, 200
        self.doc.recompute()
        grid = lighting.make_grid_target(self.doc, box, height_m=0.75, wall_band_m=0.0,
                                         spacing_m=1.0)
        self.doc.recompute()
        rect = target_mod.grid_rectangle(grid)
        self.assertAlmostEqual(rect.corner.z, 950.0)  # slab top 0.2 m + 0.75 m
        self.assertEqual((rect.nu, rect.nv), (6, 3))

    def test_luminaire_entries(self):
        area = lighting.make_luminaire(self.doc, (1.0, 2.0, 2.9), kind="Area", flux_lm=4000,
                                       maintenance_factor=0.8, width_m=1.2, length_m=0.3)
        spot = lighting.make_luminaire(self.doc, (0.0, 0.0, 3.0), kind="Spot", flux_lm=1000,
                                       maintenance_factor=1.0, aim=(1, 0, -1),
                                       beam_angle_deg=20, field_angle_deg=40)
        point = lighting.make_luminaire(self.doc, (0.5, 0.5, 1.0), kind="Point", flux_lm=100)
        self.doc.recompute()
        e = luminaire_mod.scene_entry(area)
        self.assertEqual(e["type"], "area")
        self.assertAlmostEqual(e["flux_lm"], 3200.0)
        e1, e2 = V(*e["edge1"]), V(*e["edge2"])
        self.assertAlmostEqual(e1.Length * e2.Length, 1.2 * 0.3, 9)
        normal = e1.cross(e2).normalize()
        self.assertAlmostEqual(normal.z, -1.0, 9)  # emits toward the aim (down)
        centre = V(*e["corner"]) + e1 * 0.5 + e2 * 0.5
        self.assertAlmostEqual((centre - V(1.0, 2.0, 2.9)).Length, 0.0, 9)
        s = luminaire_mod.scene_entry(spot)
        d = V(*s["direction"])
        self.assertAlmostEqual(d.x, math.sqrt(0.5), 9)
        self.assertAlmostEqual(d.z, -math.sqrt(0.5), 9)
        self.assertEqual((s["beam_angle_deg"], s["field_angle_deg"]), (20.0, 40.0))
        self.assertAlmostEqual((spot.AimDirection - V(math.sqrt(.5), 0, -math.sqrt(.5))).Length, 0, 9)
        p = luminaire_mod.scene_entry(point)
        self.assertEqual(p["position"], [0.5, 0.5, 1.0])
        self.assertAlmostEqual(p["flux_lm"], 80.0)
        self.assertFalse(area.Shape.isNull())
        self.assertFalse(point.Shape.isNull())

    def test_luminaire_checks(self):
        """Only what the document has is checked here (the maintenance factor, an area's
        size); scene values (flux, spot angles) are the solver's check (test_check)."""
        lum = lighting.make_luminaire(self.doc, flux_lm=-5, maintenance_factor=1.5)
        levels = [level for level, _ in luminaire_mod.check(lum)]
        self.assertEqual(levels.count("error"), 1)
        lum.FluxLumen, lum.MaintenanceFactor = 0.0, 0.8  # switched off: accepted
        self.assertEqual(luminaire_mod.check(lum), [])
        lum.FluxLumen = 5e6
        self.assertEqual([lv for lv, _ in luminaire_mod.check(lum)], ["warning"])
        lum.FluxLumen, lum.Width = 1000.0, 0.0
        self.assertEqual([lv for lv, _ in luminaire_mod.check(lum)], ["error"])
        with self.assertRaises(ValueError):
            lighting.make_luminaire(self.doc, kind="Laser")

    def test_undo_creation(self):
        self.doc.UndoMode = 1
        self.doc.openTransaction("Create luminaire")
        lum = lighting.make_luminaire(self.doc)
        self.doc.commitTransaction()
        name = lum.Name
        self.assertIsNotNone(self.doc.getObject(name))
        self.doc.undo()
        self.assertIsNone(self.doc.getObject(name))
        self.doc.redo()
        self.assertIsNotNone(self.doc.getObject(name))

    def test_migration_adds_missing_properties(self):
        lum = lighting.make_luminaire(self.doc)
        lum.removeProperty("SymbolSize")
        self.assertNotIn("SymbolSize", lum.PropertiesList)
        lum.Proxy.onDocumentRestored(lum)
        self.assertIn("SymbolSize", lum.PropertiesList)
        self.assertAlmostEqual(float(lum.SymbolSize), 150.0)

    def test_analysis_members(self):
        a1 = lighting.make_analysis(self.doc, name="A1")
        a2 = lighting.make_analysis(self.doc, name="A2")
        free = lighting.make_luminaire(self.doc, name="Free")
        own = lighting.make_luminaire(self.doc, name="Own", analysis=a1)
        from lighting.objects import analysis as analysis_mod

        self.assertEqual({o.Name for o in analysis_mod.luminaires(a1)}, {free.Name, own.Name})
        self.assertEqual({o.Name for o in analysis_mod.luminaires(a2)}, {free.Name})

    def test_placement_domain(self):
        doc = build_office()
        domain = doc.getObject("CeilingDomain")
        points, normal = domain_mod.candidates(domain)
        self.assertAlmostEqual(normal.z, -1.0, 9)
        self.assertEqual(domain.CandidateCount, len(points))
        self.assertGreater(len(points), 20)
        for p in points:
            self.assertAlmostEqual(p.z, 2950.0, 6)  # 5 cm under the ceiling
            self.assertTrue(-200 + 300 <= p.x <= 5200 - 300 and -200 + 300 <= p.y <= 4200 - 300)
        entry = domain_mod.metadata_entry(domain)
        self.assertEqual(entry["max_luminaires"], 6)
        self.assertEqual(len(entry["candidates"]), len(points))


class LuminaireTypeTable(DocTestCase):
    """One row per luminaire type (objects/luminaire.py KINDS), and each row's scene entry is
    exactly what the solver's reader takes for that type (it rejects missing and unknown keys)."""

    def setUp(self):
        self.doc = FreeCAD.newDocument("Kinds")

    @needs_solver
    def test_every_row_exports_an_entry_the_solver_reads(self):
        from lighting.solver import run

        lightsolver = run.load_module()
        ies = os.path.join(os.environ.get("LIGHTING_SOURCE_DIR", ""), "Resources",
                           "luminaires", "downlight.ies")
        self.assertEqual(luminaire_mod.LUMINAIRE_TYPES, tuple(luminaire_mod.KINDS))
        for kind in luminaire_mod.KINDS:
            lum = lighting.make_luminaire(self.doc, (1.0, 1.0, 2.5), kind=kind, name=kind)
            if kind == "Photometric":
                lum.PhotometricFile = ies
            self.doc.recompute()
            entry = luminaire_mod.scene_entry(lum)
            self.assertEqual(entry["type"], luminaire_mod.KINDS[kind].scene_type)
            fields = {k: v for k, v in entry.items() if k not in ("name", "type")}
            scene = lightsolver.Scene()
            scene.add_light(entry["name"], entry["type"], **fields)  # raises on a bad key

    def test_an_unknown_type_names_the_luminaire(self):
        # The property is an enumeration, so only an object from elsewhere can carry this.
        fake = type("Fake", (), {"LuminaireType": "Laser", "Label": "Odd"})()
        with self.assertRaisesRegex(ValueError, "Odd.*Laser.*Point, Spot, Area, Photometric"):
            luminaire_mod.kind_of(fake)


class BackendProperty(DocTestCase):
    """The analysis' Backend choices are the solver's registry, with a fallback without it."""

    @needs_solver
    def test_choices_are_the_solver_registry(self):
        import lightsolver  # on sys.path once needs_solver has found it

        analysis = lighting.make_analysis(FreeCAD.newDocument("Backends"))
        names = [b["name"] for b in lightsolver.backends()]
        self.assertEqual(names[0], "auto")
        self.assertEqual(analysis.getEnumerationsOfProperty("Backend"), names)
        self.assertEqual(analysis.Backend, "auto")

    def test_without_the_module_the_fallback_list_is_used(self):
        from lighting.objects import analysis as analysis_mod
        from lighting.solver import run

        saved = run.backend_names
        run.backend_names = lambda: None  # as when lightsolver cannot be imported
        try:
            analysis = lighting.make_analysis(FreeCAD.newDocument("NoSolver"))
        finally:
            run.backend_names = saved
        self.assertEqual(analysis.getEnumerationsOfProperty("Backend"),
                         list(analysis_mod.FALLBACK_BACKENDS))
        self.assertEqual(analysis.Backend, "auto")

    def test_a_value_this_build_lacks_survives_reopening(self):
        from lighting.objects import analysis as analysis_mod

        doc = FreeCAD.newDocument("OtherBuild")
        analysis = lighting.make_analysis(doc)
        # As saved by a build with a backend this one lacks.
        analysis.Backend = analysis.getEnumerationsOfProperty("Backend") + ["cuda"]
        analysis.Backend = "cuda"
        name, path = analysis.Name, os.path.join(work_dir("backend"), "other_build.FCStd")
        doc.saveAs(path)
        FreeCAD.closeDocument(doc.Name)
        analysis = FreeCAD.openDocument(path).getObject(name)
        self.assertEqual(analysis.Backend, "cuda")
        self.assertEqual(analysis.getEnumerationsOfProperty("Backend"),
                         analysis_mod.backend_choices() + ["cuda"])


class CurvedFaceGrid(DocTestCase):
    def test_a_grid_on_a_curved_face_is_refused_before_anything_is_made(self):
        """Issue 25: a grid on a cylinder's side face was accepted and then said "no area"."""
        import FreeCAD

        doc = FreeCAD.newDocument("CurvedGrid")
        cylinder = doc.addObject("Part::Cylinder", "Column")
        doc.recompute()
        before = len(doc.Objects)
        with self.assertRaises(ValueError) as caught:
            lighting.make_grid_target(doc, cylinder, face="Face1", surface="Wall")
        self.assertIn("'Column.Face1' is curved", str(caught.exception))
        self.assertIn("select a flat face", str(caught.exception))
        self.assertEqual(len(doc.Objects), before)
        grid = lighting.make_grid_target(doc, cylinder, face="Face2", surface="Ceiling")
        self.assertEqual(list(grid.Base[1]), ["Face2"])
        FreeCAD.closeDocument(doc.Name)
