"""Results live in one results object per analysis (objects/results.py): they survive save and
reopen, storing them is one undo step, input objects carry none, documents of older versions
(results on the analysis and its targets) are migrated."""
import json
import os
import zipfile

import FreeCAD

import lighting
from lighting.objects import results as results_obj
from lighting.objects.base import proxy_type
from lighting.solver import store
from wbtest import REPO, DocTestCase, build_office, needs_solver, work_dir

#: Properties older versions wrote onto inputs; none may be on a target/luminaire/analysis now.
RESULT_PROPS = set(store.LEGACY_TARGET) | set(store.LEGACY_ANALYSIS)


def fake_results(doc):
    """A results dictionary in the solver's layout for the office's three targets."""
    cells = [300.0 + 5.0 * i for i in range(48)]
    return {
        "format": "lightsolver.results/1", "photons": 1234, "partial": False, "seconds": 0.5,
        "backend": "test", "confidence": 0.95, "warnings": ["a warning"],
        "targets": [
            {"name": "Workplane", "type": "grid", "area_m2": 12.0, "mean_lux": 420.0,
             "ci_low_lux": 410.0, "ci_high_lux": 430.0, "sigma_lux": 5.0, "hits": 999,
             "cells_uv": [8, 6], "min_lux": 300.0, "max_lux": 535.0, "uniformity": 300.0 / 420.0,
             "cells": [{"lux": c, "ci_low_lux": c - 10, "ci_high_lux": c + 10, "hits": 10}
                       for c in cells]},
            {"name": "DeskTop_target", "type": "surface", "area_m2": 1.28, "mean_lux": 510.0,
             "ci_low_lux": 490.0, "ci_high_lux": 530.0, "sigma_lux": 10.0, "hits": 50},
            {"name": "NorthWall", "type": "surface", "area_m2": 15.0, "mean_lux": 140.0,
             "ci_low_lux": 135.0, "ci_high_lux": 145.0, "sigma_lux": 2.5, "hits": 70},
        ]}


def results_objects(doc):
    return [o for o in doc.Objects if proxy_type(o) == results_obj.TYPE]


def inputs_with_results(doc):
    """'Object.Property' for every result property found on a non-results object."""
    return sorted(f"{o.Name}.{p}" for o in doc.Objects for p in o.PropertiesList
                  if p in RESULT_PROPS and proxy_type(o) != results_obj.TYPE)


class Persistence(DocTestCase):
    def _reopen(self, doc, name="office.FCStd"):
        path = self.saved = os.path.join(work_dir("save"), name)
        doc.saveAs(path)
        FreeCAD.closeDocument(doc.Name)
        return FreeCAD.openDocument(path)

    def test_stored_results_survive_reopen(self):
        doc = build_office()
        analysis = doc.getObject("LightingAnalysis")
        before = store.apply_to_document(analysis, fake_results(doc))
        table = before.table()
        print("\n" + table)
        self.assertIn("FAIL", table)  # 420 lx < 500 lx required
        self.assertEqual(inputs_with_results(doc), [])
        doc = self._reopen(doc)
        analysis = doc.getObject("LightingAnalysis")
        stored = results_obj.of_analysis(analysis)
        self.assertIsNotNone(stored)
        # The derived properties are not saved: they are rebuilt from the JSON on restore.
        for name in results_obj.DERIVED:
            self.assertIn("Transient", stored.getPropertyStatus(name), name)
        with zipfile.ZipFile(self.saved) as archive:
            xml = archive.read("Document.xml").decode("utf-8")
        self.assertEqual(xml.count("&quot;lightsolver.results/1&quot;"), 1)  # one copy
        self.assertNotIn('value="420', xml)  # Em is in the JSON only
        self.assertEqual(results_obj.mean_lux(stored, "Workplane"), 420.0)
        self.assertEqual(results_obj.cells_lux(stored, "Workplane"),
                         [300.0 + 5.0 * i for i in range(48)])
        self.assertEqual(results_obj.cells_lux(stored, "NorthWall"), [])
        self.assertEqual(list(stored.CiHighLux), [430.0, 530.0, 145.0])
        # No Emin interval in results that judged no requirement (docs/statistics.md).
        self.assertIsNone(lighting.results(doc)["Workplane"].min_ci_lux)
        self.assertEqual(analysis.Status, "done")
        self.assertEqual(list(stored.Warnings), ["a warning"])
        self.assertEqual(stored.Photons, 1234.0)
        self.assertEqual(lighting.results(doc).table(), table)
        # The proxies work after the reopen (execute, checks).
        doc.recompute()
        self.assertEqual(len(doc.getObject("Workplane").Shape.Faces), 48)
        self.assertTrue(lighting.check(doc, need_solver=False).ok)

    def test_results_are_one_undo_step(self):
        doc = build_office()
        doc.UndoMode = 1
        analysis = doc.getObject("LightingAnalysis")
        store.apply_to_document(analysis, fake_results(doc))
        self.assertEqual(len(results_objects(doc)), 1)
        doc.undo()
        self.assertEqual(results_objects(doc), [])
        self.assertIsNone(lighting.results(doc))
        doc.redo()
        self.assertEqual(lighting.results(doc)["Workplane"].mean_lux, 420.0)
        # A second run updates the same object.
        second = fake_results(doc)
        second["targets"][0]["mean_lux"] = 400.0
        store.apply_to_document(analysis, second)
        self.assertEqual(len(results_objects(doc)), 1)
        self.assertEqual(results_obj.mean_lux(results_objects(doc)[0], "Workplane"), 400.0)
        store.clear(analysis)
        self.assertEqual(results_objects(doc), [])
        self.assertIsNone(lighting.results(doc))
        self.assertEqual(analysis.Status, "not run")
        doc.undo()
        self.assertEqual(lighting.results(doc)["Workplane"].mean_lux, 400.0)

    def test_removing_the_analysis_takes_its_results_along(self):
        """A script's removeObject (not only the GUI's Delete) leaves no orphan results
        object; one Undo brings both back."""
        doc = build_office()
        doc.UndoMode = 1
        analysis = doc.getObject("LightingAnalysis")
        store.apply_to_document(analysis, fake_results(doc))
        self.assertEqual(len(results_objects(doc)), 1)
        doc.openTransaction("Delete analysis")
        doc.removeObject("LightingAnalysis")
        doc.commitTransaction()
        self.assertEqual(results_objects(doc), [])
        doc.undo()
        self.assertIsNotNone(doc.getObject("LightingAnalysis"))
        self.assertEqual(len(results_objects(doc)), 1)
        self.assertEqual(lighting.results(doc)["Workplane"].mean_lux, 420.0)

    def test_old_document_is_migrated(self):
        """A file of an older version: results on the analysis and its targets."""
        doc = build_office()
        analysis = doc.getObject("LightingAnalysis")
        text = json.dumps(fake_results(doc))
        analysis.addProperty("App::PropertyString", "ResultsJson", "Results")
        analysis.addProperty("App::PropertyFloat", "PhotonsTraced", "Results")
        analysis.ResultsJson, analysis.PhotonsTraced = text, 1234.0
        grid = doc.getObject("Workplane")
        grid.addProperty("App::PropertyFloat", "MeanLux", "Results")
        grid.addProperty("App::PropertyFloatList", "CellsLux", "Results")
        grid.MeanLux, grid.CellsLux = 420.0, [1.0, 2.0]
        doc = self._reopen(doc, "old.FCStd")
        result = lighting.results(doc)  # the first use migrates
        self.assertEqual(result["Workplane"].mean_lux, 420.0)
        self.assertEqual(len(results_objects(doc)), 1)
        self.assertEqual(json.loads(results_objects(doc)[0].ResultsJson), json.loads(text))
        self.assertEqual(inputs_with_results(doc), [])

    def test_results_of_an_older_solver_read_as_the_report_reads_them(self):
        """One reader (lightsolver_results) for the workbench and the report: a grid without
        Emin/Emax/U0 (the oldest results) gets them from its cells in its migration step, the
        same values the report prints, and the stored document is left as it was."""
        from lighting.solver.results import AnalysisResult, reader

        data = fake_results(None)
        for key in ("min_lux", "max_lux", "uniformity"):
            data["targets"][0].pop(key)
        before = json.dumps(data, sort_keys=True)
        grid = AnalysisResult.from_data(data)["Workplane"]
        self.assertEqual((grid.min_lux, grid.max_lux), (300.0, 535.0))
        self.assertAlmostEqual(grid.uniformity, 300.0 / 420.0, places=15)
        # Not the lowest cell's own interval: only the solver's, simultaneous over the cells.
        self.assertIsNone(grid.min_ci_lux)
        self.assertIsNone(grid.uniformity_ci)
        self.assertEqual(json.dumps(data, sort_keys=True), before)
        read = reader().read(data, strict=False)
        self.assertEqual(read["Workplane"].emin.value, grid.min_lux)
        self.assertTrue(any("grid statistics derived from the cells" in n for n in read.notes))
        self.assertEqual(reader().__name__, "lightsolver_results")

    def test_results_without_verdicts_show_the_estimates_as_before(self):
        """Results without the solver's verdicts (older versions; fake_results has none) and
        the office's requirements (work plane 500 lx, U0 0.60; desk 500 lx; north wall
        150 lx): the reader judges the point estimates, and the workbench shows the texts it
        showed when it judged them itself ("(est.)" in the table and the status line,
        "(estimate)" in the plan view's caption)."""
        from lighting import plots

        doc = build_office()
        analysis = doc.getObject("LightingAnalysis")
        result = store.apply_to_document(analysis, fake_results(doc))
        checks = [line.split("  ")[-1] for line in result.table().splitlines()[2:5]]
        self.assertEqual(checks, ["FAIL (est.)", "pass (est.)", "FAIL (est.)"])
        self.assertEqual([t.verdict_text() for t in result.targets],
                         ["FAIL (est.)", "pass (est.)", "FAIL (est.)"])
        self.assertTrue(all(t.estimated for t in result.targets))
        self.assertIsNone(result.verdict)  # the solver judged nothing
        self.assertIn("Workplane Em 420 lx U0 0.71 FAIL (est.)", store.summary_line(result))
        caption = plots.grid_plot_data(analysis, doc.getObject("Workplane")).caption()
        self.assertIn("required: Em \u2265 500 lx (NOT met (estimate)), "
                      "U0 \u2265 0.6 (met (estimate))", caption)
        # The solver's verdicts, when the results carry them, are shown as they are.
        judged = fake_results(doc)
        judged["targets"][0].update(requirements={"em_lux": 400.0}, verdict="undecided",
                                    verdicts={"em": {"verdict": "undecided", "value": 420.0,
                                                     "ci_low": 410.0, "ci_high": 430.0,
                                                     "required": 400.0, "relation": ">=",
                                                     "to_decide": {"photons": None,
                                                                   "seconds": None}}})
        result = store.apply_to_document(analysis, judged)
        self.assertEqual(result["Workplane"].verdict_text(), "undecided")
        self.assertFalse(result["Workplane"].estimated)
        caption = plots.grid_plot_data(analysis, doc.getObject("Workplane")).caption()
        self.assertIn("required: Em \u2265 400 lx (undecided)", caption)  # what was judged

    @needs_solver
    def test_solved_results_survive_reopen(self):
        """After a run: one results object per analysis, holding JSON that the schema
        validates; no target/luminaire/analysis carries result properties; save + reopen keeps
        the results object and its JSON unchanged."""
        import jsonschema

        doc = build_office(photons=50000)
        doc.getObject("LightingAnalysis").Decide = False  # exactly the photons asked for
        second = lighting.make_analysis(doc, "SecondAnalysis", photons=20000)
        lighting.make_luminaire(doc, (2.5, 2.0, 2.5), kind="Point", flux_lm=1000.0,
                                name="SecondLamp", analysis=second)
        lighting.make_grid_target(doc, doc.getObject("Workplane").Base[0], spacing_m=1.0,
                                  name="SecondGrid", analysis=second)
        doc.recompute()
        result = lighting.analyze(doc, output_dir=work_dir("solved"))
        lighting.analyze(doc, analysis=second, output_dir=work_dir("solved2"))
        found = results_objects(doc)
        self.assertEqual(len(found), 2)
        owners = sorted(results_obj.analysis_of(o).Name for o in found)
        self.assertEqual(owners, ["LightingAnalysis", "SecondAnalysis"])
        with open(os.path.join(REPO, "docs", "schemas", "results.schema.json"),
                  encoding="utf-8") as stream:
            schema = json.load(stream)
        texts = {}
        for obj in found:
            jsonschema.validate(json.loads(obj.ResultsJson), schema)
            texts[obj.Name] = obj.ResultsJson
        self.assertEqual(inputs_with_results(doc), [])
        doc = self._reopen(doc)
        again = lighting.results(doc)
        self.assertEqual(again.table(), result.table())
        self.assertEqual({o.Name: o.ResultsJson for o in results_objects(doc)}, texts)
        stored = results_obj.of_analysis(doc.getObject("LightingAnalysis"))
        self.assertEqual(results_obj.cells_lux(stored, "Workplane"), result["Workplane"].cells_lux)
        self.assertEqual(stored.Photons, 50000)
        self.assertEqual(inputs_with_results(doc), [])
