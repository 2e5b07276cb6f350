"""Results survive save and reopen; storing them is one undo step."""
import os

import FreeCAD

import lighting
from lighting.solver import store
from wbtest import DocTestCase, build_office, needs_solver, work_dir


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


class Persistence(DocTestCase):
    def _reopen(self, doc):
        path = os.path.join(work_dir("save"), "office.FCStd")
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
        doc = self._reopen(doc)
        grid = doc.getObject("Workplane")
        self.assertTrue(grid.HasResults)
        self.assertEqual(grid.MeanLux, 420.0)
        self.assertEqual(list(grid.CellsLux), [300.0 + 5.0 * i for i in range(48)])
        self.assertEqual(grid.MinCiLowLux, 290.0)
        self.assertEqual(doc.getObject("NorthWall").CiHighLux, 145.0)
        analysis = doc.getObject("LightingAnalysis")
        self.assertEqual(analysis.Status, "done")
        self.assertEqual(list(analysis.SolverWarnings), ["a warning"])
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
        self.assertTrue(doc.getObject("Workplane").HasResults)
        doc.undo()
        self.assertFalse(doc.getObject("Workplane").HasResults)
        self.assertEqual(analysis.ResultsJson, "")
        doc.redo()
        self.assertEqual(doc.getObject("Workplane").MeanLux, 420.0)
        store.clear(analysis)
        self.assertFalse(doc.getObject("DeskTop_target").HasResults)
        self.assertIsNone(lighting.results(doc))

    @needs_solver
    def test_solved_results_survive_reopen(self):
        doc = build_office(photons=50000)
        result = lighting.analyze(doc, output_dir=work_dir("solved"))
        doc = self._reopen(doc)
        again = lighting.results(doc)
        self.assertEqual(again.table(), result.table())
        self.assertEqual(list(doc.getObject("Workplane").CellsLux), result["Workplane"].cells_lux)
        self.assertEqual(doc.getObject("LightingAnalysis").PhotonsTraced, 50000)
