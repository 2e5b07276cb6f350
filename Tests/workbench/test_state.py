"""The model state is always true (issue 12, items 1, 3 and 10).

- Hidden objects stay in the lighting model; only an explicit exclusion (``LightingExclude``,
  ``lighting.exclude``) leaves an object out, and Check lists what is left out and why.
- Stored results know whether they still describe the model: any change of what the run
  exported (flux, material, placement, settings, exclusion) makes them stale, undo and a
  new run make them current again; the saved Status never says "checking".
- One undo step per user action that changed something: Check and a second Run of an
  unchanged model add none."""
import os
import zipfile

import FreeCAD

import lighting
from lighting.export import collect, fingerprint
from lighting.objects import results as results_obj
from lighting.solver import machine, store
from wbtest import DocTestCase, build_office, needs_solver, work_dir

PHOTONS = 20000


def ceiling(doc):
    return doc.getObjectsByLabel("Ceiling")[0]


def em(result, name="Workplane"):
    return result[name].mean_lux


def saved_status(path):
    """The analysis' Status as written in a saved .FCStd."""
    import xml.etree.ElementTree as ElementTree

    with zipfile.ZipFile(path) as archive:
        root = ElementTree.fromstring(archive.read("Document.xml"))
    for element in root.find("ObjectData"):
        if element.get("name") == "LightingAnalysis":
            for prop in element.iter("Property"):
                if prop.get("name") == "Status":
                    return prop.find("String").get("value")
    return None


class Exclusion(DocTestCase):
    def setUp(self):
        self.doc = build_office(photons=PHOTONS)

    def test_hidden_objects_are_exported(self):
        ceil = ceiling(self.doc)
        ceil.Visibility = False
        names = {o.Name for o in collect.exported_objects(self.doc)}
        self.assertIn(ceil.Name, names)
        self.assertEqual(collect.left_out(self.doc)[0][0].Label, "Office")  # only the space

    def test_exclude_and_include(self):
        ceil = ceiling(self.doc)
        self.doc.UndoMode = 1
        undo_before = self.doc.UndoCount
        self.assertEqual(lighting.exclude(ceil), [ceil])
        self.assertTrue(ceil.LightingExclude)
        self.assertEqual(self.doc.UndoCount, undo_before + 1)
        self.assertEqual(self.doc.UndoNames[0], "Exclude from lighting")
        self.assertNotIn(ceil.Name, {o.Name for o in collect.exported_objects(self.doc)})
        self.assertEqual(lighting.exclude(ceil), [])  # already excluded: no undo step
        self.assertEqual(self.doc.UndoCount, undo_before + 1)
        self.doc.undo()  # the property goes away with the undo
        self.assertNotIn(collect.EXCLUDE_PROPERTY, ceil.PropertiesList)
        self.assertIn(ceil.Name, {o.Name for o in collect.exported_objects(self.doc)})
        self.doc.redo()
        self.assertTrue(ceil.LightingExclude)
        lighting.exclude([ceil], False)
        self.assertIn(ceil.Name, {o.Name for o in collect.exported_objects(self.doc)})
        with self.assertRaises(ValueError):
            lighting.exclude(self.doc.getObject("Luminaire01"))

    def test_exclusion_survives_save_and_reopen(self):
        lighting.exclude(ceiling(self.doc))
        path = os.path.join(work_dir("exclude"), "excluded.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        doc = FreeCAD.openDocument(path)
        self.assertTrue(ceiling(doc).LightingExclude)
        self.assertNotIn(ceiling(doc).Name, {o.Name for o in collect.exported_objects(doc)})

    def test_container_exclusion(self):
        part = self.doc.addObject("App::Part", "Furniture")
        part.addObject(self.doc.getObject("Cabinet"))
        self.doc.recompute()
        self.assertIn("Cabinet", {o.Name for o in collect.exported_objects(self.doc)})
        lighting.exclude(part)
        self.assertNotIn("Cabinet", {o.Name for o in collect.exported_objects(self.doc)})
        reasons = {o.Name: r for o, r in lighting.left_out(self.doc)}
        self.assertIn("excluded with 'Furniture'", reasons["Cabinet"])
        self.assertIn("with everything in it", reasons["Furniture"])

    def test_check_lists_what_is_left_out(self):
        ceil = ceiling(self.doc)
        ceil.Visibility = False
        report = lighting.check(self.doc, need_solver=False)
        texts = [m.text for m in report.messages]
        # Hidden: still in, and Check says so (nothing about it being left out).
        self.assertFalse(any("'Ceiling' is left out" in t for t in texts), texts)
        self.assertTrue(any(t.startswith("Hidden but in the lighting model: 'Ceiling'")
                            for t in texts), texts)
        lighting.exclude(ceil)
        wire = self.doc.addObject("Part::Feature", "Outline")
        import Part

        wire.Shape = Part.makePolygon([FreeCAD.Vector(), FreeCAD.Vector(1000, 0, 0),
                                       FreeCAD.Vector(1000, 1000, 0)])
        report = lighting.check(self.doc, need_solver=False)
        found = {m.object_name: (m.level, m.text) for m in report.messages}
        self.assertEqual(found[ceil.Name][0], "info")
        self.assertIn("'Ceiling' is left out of the lighting model: excluded from lighting",
                      found[ceil.Name][1])
        self.assertIn("has no faces", found["Outline"][1])
        self.assertIn("is an Arch space", found[self.doc.getObjectsByLabel("Office")[0].Name][1])
        self.assertTrue(report.ok)

    def test_check_says_hidden_objects_stay_in(self):
        desk = self.doc.getObject("Desk")
        desk.Visibility = False
        texts = [m.text for m in lighting.check(self.doc, need_solver=False).messages]
        self.assertIn("Hidden but in the lighting model: 'Desk' (hiding is only a view; use "
                      "Exclude from lighting to leave an object out)", texts)

    def test_thickness_consumes_its_base(self):
        box = self.doc.addObject("Part::Box", "Shell")
        self.doc.recompute()
        thick = self.doc.addObject("Part::Thickness", "Hollow")
        thick.Faces = (box, ["Face6"])
        thick.Value = 10.0
        self.doc.recompute()
        names = {o.Name for o in collect.exported_objects(self.doc)}
        self.assertIn("Hollow", names)
        self.assertNotIn("Shell", names)


class Naming(DocTestCase):
    def test_face_target_is_named_after_its_faces(self):
        doc = build_office(photons=PHOTONS)
        walls = doc.getObjectsByLabel("Walls")[0]
        desk = doc.getObject("Desk")
        one = lighting.make_face_target(doc, [(walls, "Face3")])
        self.assertEqual(one.Label, f"Target {walls.Label} Face3")
        many = lighting.make_face_target(doc, [(desk, ["Face1", "Face2"]), (walls, "Face4")])
        self.assertEqual(many.Label, f"Target {desk.Label} Face1, Face2 +1 face")
        self.assertEqual(lighting.make_face_target(doc, [(desk, "Face5")], name="Mine").Label,
                         "Mine")


class SolvedState(DocTestCase):
    """Needs the solver: same seed and photons give bit-identical results."""

    def _analyze(self, doc, tag):
        return lighting.analyze(doc, output_dir=work_dir(tag))

    @needs_solver
    def test_hidden_ceiling_changes_nothing_excluded_changes_the_scene(self):
        doc = build_office(photons=PHOTONS)
        shown = self._analyze(doc, "shown")
        ceil = ceiling(doc)
        ceil.Visibility = False
        hidden = self._analyze(doc, "hidden")
        self.assertEqual(em(hidden), em(shown))  # bit-identical
        self.assertEqual(hidden["Workplane"].cells_lux, shown["Workplane"].cells_lux)
        self.assertEqual(lighting.results_state(doc).state, "current")
        lighting.exclude(ceil)
        self.assertTrue(lighting.results_state(doc).stale)
        self.assertIn("'Ceiling' left out", lighting.results_state(doc).changes)
        excluded = self._analyze(doc, "excluded")
        self.assertLess(em(excluded), em(shown))  # no ceiling: no light reflected down
        print(f"\nEm shown {em(shown):.1f} lx, hidden {em(hidden):.1f} lx, "
              f"excluded {em(excluded):.1f} lx")

    @needs_solver
    def test_edits_make_results_stale_and_a_run_current(self):
        doc = build_office(photons=PHOTONS)
        doc.UndoMode = 1
        self.assertEqual(lighting.results_state(doc).state, "none")
        self._analyze(doc, "first")
        self.assertEqual(lighting.results_state(doc).state, "current")
        lum = doc.getObject("Luminaire01")
        edits = [
            ("flux", lambda: setattr(lum, "FluxLumen", 2 * lum.FluxLumen),
             "luminaire 'Luminaire01' changed"),
            ("material", lambda: setattr(doc.getObject("Desk"), "Reflectance", 0.8),
             "'Desk' changed"),
            ("placement", lambda: setattr(doc.getObject("Cabinet"), "Placement",
                                          FreeCAD.Placement(FreeCAD.Vector(3000, 3750, 600),
                                                            FreeCAD.Rotation())),
             "'Cabinet' changed"),
            ("settings", lambda: setattr(doc.getObject("LightingAnalysis"), "Seed", 7),
             "analysis settings changed"),
        ]
        for name, edit, change in edits:
            undo_before = doc.UndoCount
            doc.openTransaction(f"edit {name}")
            edit()
            doc.commitTransaction()
            doc.recompute()
            state = lighting.results_state(doc)
            self.assertTrue(state.stale, name)
            self.assertEqual(state.changes, [change], name)
            self.assertIn("out of date", state.text())
            doc.undo()  # undo brings the model back: the results describe it again
            doc.recompute()
            self.assertEqual(lighting.results_state(doc).state, "current", name)
            self.assertEqual(doc.UndoCount, undo_before, name)
        # Hiding, relabelling and display settings are not model changes.
        ceiling(doc).Visibility = False
        doc.getObject("Luminaire02").Label = "Lamp over the desk"
        doc.getObject("LightingAnalysis").ColorMap = "Heat"
        doc.getObject("Workplane").RequiredLux = 300.0  # pass/FAIL is judged live
        self.assertEqual(lighting.results_state(doc).state, "current")
        lum.FluxLumen = 2 * lum.FluxLumen
        self.assertTrue(lighting.results_state(doc).stale)
        self._analyze(doc, "again")
        self.assertEqual(lighting.results_state(doc).state, "current")

    @needs_solver
    def test_run_twice_adds_no_undo_step_and_check_none(self):
        doc = build_office(photons=PHOTONS)
        doc.UndoMode = 1
        analysis = doc.getObject("LightingAnalysis")
        folder = work_dir("once")
        lighting.analyze(doc, output_dir=folder)
        count = doc.UndoCount
        self.assertEqual(doc.UndoNames[0], "Lighting results")
        lighting.analyze(doc, output_dir=folder)
        self.assertEqual(doc.UndoCount, count)  # same model, same seed: nothing changed
        # Check (as the task panel does it, settings written first) adds no step either, and
        # leaves Status as it was.
        self.assertFalse(store.write_settings(analysis, Photons=PHOTONS, TargetAccuracy=0.0))
        machine.AnalysisRun(analysis).check()
        self.assertEqual(analysis.Status, "done")
        doc.getObject("Luminaire01").Label = "renamed after the check"
        self.assertEqual(doc.UndoCount, count)
        self.assertTrue(store.write_settings(analysis, Photons=PHOTONS + 1))
        self.assertEqual(doc.UndoCount, count + 1)
        self.assertEqual(doc.UndoNames[0], "Lighting settings")

    @needs_solver
    def test_saved_status_is_never_a_stage(self):
        doc = build_office(photons=PHOTONS)
        analysis = doc.getObject("LightingAnalysis")
        job = machine.AnalysisRun(analysis)
        job.check()
        self.assertEqual(analysis.Status, "not run")
        folder = work_dir("saved")
        path = os.path.join(folder, "checked.FCStd")
        doc.saveAs(path)
        self.assertEqual(saved_status(path), "not run")
        self._analyze(doc, "saved-run")
        machine.AnalysisRun(analysis).check()
        doc.save()
        self.assertEqual(saved_status(path), "done")
        # A file an older version saved in the middle of a check opens in its real state.
        analysis.Status = "checking"
        doc.save()
        FreeCAD.closeDocument(doc.Name)
        doc = FreeCAD.openDocument(path)
        self.assertEqual(doc.getObject("LightingAnalysis").Status, "done")
        self.assertEqual(lighting.results_state(doc).state, "current")  # survives reopen
        doc.getObject("Luminaire03").FluxLumen = 100.0
        self.assertTrue(lighting.results_state(doc).stale)

    def test_fingerprint_ignores_visibility_and_caches_shapes(self):
        doc = build_office(photons=PHOTONS)
        analysis = doc.getObject("LightingAnalysis")
        before = fingerprint.of_analysis(analysis)
        ceiling(doc).Visibility = False
        self.assertEqual(fingerprint.of_analysis(analysis), before)
        key = (doc.Name, ceiling(doc).Name)
        self.assertIn(key, fingerprint._shape_cache)
        ceiling(doc).Height = 300.0  # an edit drops the cached signature
        self.assertNotIn(key, fingerprint._shape_cache)
        doc.recompute()
        self.assertNotEqual(fingerprint.of_analysis(analysis)[f"object:{ceiling(doc).Name}"],
                            before[f"object:{ceiling(doc).Name}"])

    def test_arch_material_edit_makes_results_stale(self):
        from lighting.compat import import_arch
        from test_persistence import fake_results

        doc = build_office(photons=PHOTONS)
        analysis = doc.getObject("LightingAnalysis")
        walls = doc.getObjectsByLabel("Walls")[0]
        material = import_arch().makeMaterial("Plaster")
        material.Material = dict(material.Material, Reflectance="80 %")
        walls.Material = material
        doc.recompute()
        store.apply_to_document(analysis, fake_results(doc))
        self.assertEqual(lighting.results_state(doc).state, "current")
        material.Material = dict(material.Material, Reflectance="60 %")
        self.assertEqual(lighting.results_state(doc).changes, ["'Walls' changed"])

    def test_results_of_older_versions_are_unknown(self):
        doc = build_office(photons=PHOTONS)
        analysis = doc.getObject("LightingAnalysis")
        from test_persistence import fake_results

        store.apply_to_document(analysis, fake_results(doc))
        self.assertEqual(lighting.results_state(doc).state, "current")
        results_obj.of_analysis(analysis).InputsFingerprint = ""
        self.assertEqual(lighting.results_state(doc).state, "unknown")
