"""lighting.report(doc, path): the calculation report of an analysis' stored results, headless
(docs/report.md): HTML and PDF from the office example, no results, stale results, a missing
scene file."""
import os


import lighting
from lighting.messages import CheckError
from wbtest import DocTestCase, build_office, needs_solver, work_dir

DATE = "2026-01-01"


class ReportTest(DocTestCase):
    @needs_solver
    def test_office_report_as_html_and_pdf(self):
        doc = build_office(photons=20000, seed=3)
        folder = work_dir("report")
        lighting.analyze(doc, output_dir=folder)
        results = lighting.results(doc)
        html_path = os.path.join(folder, "office report.html")
        self.assertEqual(lighting.report(doc, html_path, date=DATE), html_path)
        with open(html_path, encoding="utf-8") as f:
            html = f.read()
        from lighting.reporting import report_module

        fmt = report_module().fmt
        for label in ("Workplane", "Desk top", "North wall", DATE, doc.Label):
            self.assertIn(label, html)
        for target in results.targets:
            self.assertIn(fmt.lux(target.mean_lux), html)
        # the floor plan, the picture of the model, the workplane's plan and value chart
        self.assertEqual(html.count("<svg"), 4)
        self.assertIn("0.80", html)  # the luminaires' maintenance factor
        self.assertNotIn("out of date", html)
        # The same stored results give the same page again.
        again = os.path.join(folder, "again.html")
        lighting.report(doc, again, date=DATE)
        with open(again, encoding="utf-8") as f:
            self.assertEqual(f.read(), html)
        pdf = os.path.join(folder, "office report.pdf")
        lighting.report(doc, pdf, date=DATE)
        with open(pdf, "rb") as f:
            self.assertEqual(f.read(5), b"%PDF-")

    @needs_solver
    def test_stale_results_and_a_missing_scene_file_are_said(self):
        doc = build_office(photons=20000, seed=3)
        folder = work_dir("report-stale")
        lighting.analyze(doc, output_dir=folder)
        scene_file = doc.getObject("LightingAnalysis").SceneFile
        os.remove(scene_file)
        doc.getObject("Luminaire01").FluxLumen = 3000.0
        doc.recompute()
        path = lighting.report(doc, os.path.join(folder, "stale.html"), date=DATE)
        with open(path, encoding="utf-8") as f:
            html = f.read()
        self.assertIn("results out of date (stale)", html)
        self.assertIn("exported again for this report", html)
        self.assertTrue(os.path.isfile(scene_file))  # exported again

    def test_no_results_is_a_check_error(self):
        doc = build_office(photons=20000, seed=3)
        with self.assertRaises(CheckError) as caught:
            lighting.report(doc, os.path.join(work_dir("report-none"), "r.html"))
        self.assertIn("run the analysis first", str(caught.exception))
