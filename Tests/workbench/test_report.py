"""lighting.report(doc, path): the calculation report of an analysis' stored results, headless
(docs/report.md): HTML and PDF from the office example, no results, stale results (refused
unless allow_stale, then said), partial results (refused unless allow_partial), a missing
scene file, a missing output folder, the sign-off fields, the two-step job the GUI's worker
thread runs."""
import json
import os


import lighting
from lighting.messages import CheckError, LightingError
from lighting.reporting import PartialResultsError, StaleResultsError
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
    def test_stale_results_are_refused_unless_allowed_then_said(self):
        doc = build_office(photons=20000, seed=3)
        folder = work_dir("report-stale")
        lighting.analyze(doc, output_dir=folder)
        luminaire = doc.getObject("Luminaire01")
        flux = luminaire.FluxLumen
        luminaire.FluxLumen = 3000.0
        doc.recompute()
        before = sorted(os.listdir(folder))
        path = os.path.join(folder, "stale.html")
        with self.assertRaises(StaleResultsError) as caught:
            lighting.report(doc, path, date=DATE)
        message = str(caught.exception)
        for part in ("out of date (stale)", "Luminaire01", "allow_stale=True"):
            self.assertIn(part, message)
        self.assertEqual(sorted(os.listdir(folder)), before)  # nothing written
        self.assertEqual(lighting.report(doc, path, date=DATE, allow_stale=True), path)
        with open(path, encoding="utf-8") as f:
            self.assertIn("results out of date (stale)", f.read())
        # Put back, the results describe the model again: written without a word of it.
        luminaire.FluxLumen = flux
        doc.recompute()
        current = os.path.join(folder, "current.html")
        lighting.report(doc, current, date=DATE)
        with open(current, encoding="utf-8") as f:
            self.assertNotIn("out of date", f.read())

    @needs_solver
    def test_partial_results_are_refused_unless_allowed(self):
        from lighting.solver import store

        doc = build_office(photons=20000, seed=3)
        folder = work_dir("report-partial")
        lighting.analyze(doc, output_dir=folder)
        analysis = doc.getObject("LightingAnalysis")
        obj = store.results_object(analysis)
        data = dict(json.loads(obj.ResultsJson), partial=True, stop_reason="cancelled",
                    photons=7000)
        store.apply_to_document(analysis, data, obj.SceneFile, obj.ResultsFile)
        before = sorted(os.listdir(folder))
        path = os.path.join(folder, "partial.html")
        with self.assertRaises(PartialResultsError) as caught:
            lighting.report(doc, path, date=DATE)
        self.assertIn("7,000 photons", str(caught.exception))
        self.assertIn("allow_partial=True", str(caught.exception))
        self.assertEqual(sorted(os.listdir(folder)), before)
        lighting.report(doc, path, date=DATE, allow_partial=True)
        with open(path, encoding="utf-8") as f:
            self.assertIn("Partial results", f.read())

    @needs_solver
    def test_a_missing_folder_is_refused_and_not_created(self):
        doc = build_office(photons=20000, seed=3)
        folder = work_dir("report-folder")
        lighting.analyze(doc, output_dir=folder)
        missing = os.path.join(folder, "no such folder")
        with self.assertRaises(LightingError) as caught:
            lighting.report(doc, os.path.join(missing, "r.pdf"), date=DATE)
        self.assertIn("does not exist", str(caught.exception))
        self.assertFalse(os.path.exists(missing))
        with self.assertRaises(LightingError):
            lighting.report(doc, os.path.join(folder, "r.docx"), date=DATE)

    @needs_solver
    def test_the_job_writes_on_a_worker_thread_with_the_documents_signoff(self):
        from lighting.reporting import prepare_report, signoff_of

        doc = build_office(photons=20000, seed=3)
        doc.CreatedBy = "A. Writer"
        doc.Company = "Lux & Co"
        folder = work_dir("report-job")
        lighting.analyze(doc, output_dir=folder)
        analysis = doc.getObject("LightingAnalysis")
        self.assertEqual(signoff_of(doc), {"project": doc.Label,
                                           "author": "A. Writer, Lux & Co", "checked_by": ""})
        job = prepare_report(analysis, os.path.join(folder, "job.html"), date=DATE,
                             signoff={"checked_by": "K. Lux"})
        self.assertEqual(job.signoff["checked_by"], "K. Lux")
        self.assertEqual(job.signoff["author"], "A. Writer, Lux & Co")
        job.start()
        self.assertTrue(job.wait(120))
        self.assertIsNone(job.error)
        self.assertEqual(job.written, os.path.join(folder, "job.html"))
        direct = lighting.report(doc, os.path.join(folder, "direct.html"), date=DATE,
                                 signoff={"checked_by": "K. Lux"})
        with open(job.written, encoding="utf-8") as a, open(direct, encoding="utf-8") as b:
            self.assertEqual(a.read(), b.read())  # the thread writes what the call writes
        # A refusal on the worker is kept for the GUI thread, with nothing written.
        bad = prepare_report(analysis, os.path.join(folder, "bad.html"), date=DATE)
        bad.data = {"format": "lightsolver.results/1"}
        bad.start()
        self.assertTrue(bad.wait(60))
        self.assertIsInstance(bad.error, LightingError)
        self.assertIn("no targets", str(bad.error))
        self.assertFalse(os.path.exists(os.path.join(folder, "bad.html")))

    @needs_solver
    def test_stale_results_and_a_missing_scene_file_are_said(self):
        doc = build_office(photons=20000, seed=3)
        folder = work_dir("report-stale")
        lighting.analyze(doc, output_dir=folder)
        scene_file = doc.getObject("LightingAnalysis").SceneFile
        os.remove(scene_file)
        doc.getObject("Luminaire01").FluxLumen = 3000.0
        doc.recompute()
        path = lighting.report(doc, os.path.join(folder, "stale.html"), date=DATE,
                               allow_stale=True)
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
