"""lighting.report(doc, path): the calculation report of an analysis' stored results, headless
(docs/report.md): HTML and PDF from the office example, no results, stale results (refused
unless allow_stale, then said), partial results (refused unless allow_partial), a missing
scene file, a missing output folder, the sign-off fields, the two-step job the GUI's worker
thread runs; the analysis' report inputs (group "Report": project, sign-off names, date
policy, LENI inputs) on the page, kept through save and reopen, refused by name when unusable;
the results as traced with every light scene of the document, whatever scene is shown."""
import hashlib
import json
import os

import FreeCAD

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


def _sha256(path):
    with open(path, "rb") as stream:
        return hashlib.sha256(stream.read()).hexdigest()


def _read(path):
    with open(path, encoding="utf-8") as stream:
        return stream.read()


#: The report inputs an architect fills in (objects/report_settings.py).
INPUTS = {"ProjectName": "Office refurbishment, 3rd floor", "ProjectNumber": "2026-014",
          "Client": "Müller AG", "PreparedBy": "A. Architect", "CheckedBy": "K. Checker",
          "ReportDate": "Fixed", "FixedDate": "2026-02-03", "EnergyEstimate": True,
          "OperatingHoursDay": 2000.0, "OperatingHoursNight": 400.0, "OccupancyFactor": 0.9,
          "DaylightDependencyFactor": 0.8, "ConstantIlluminanceFactor": 0.95,
          "ParasiticEnergy": 1.5, "EnergyFloorArea": 15.0}


class ReportInputs(DocTestCase):
    """The analysis' group "Report" reaches the sign-off block, the cover and LENI."""

    def _office_with_power(self, folder):
        """The office with the batwing IES panels (36 W each, from the file) and a run."""
        doc = build_office(photons=20000, seed=3)
        ies = os.path.join(os.environ["LIGHTING_SOURCE_DIR"], "Resources", "luminaires",
                           "batwing_panel.ies")
        luminaires = [o for o in doc.Objects if o.Name.startswith("Luminaire0")]
        lighting.assign_photometry(doc, luminaires, ies)
        doc.recompute()
        lighting.analyze(doc, output_dir=folder)
        return doc, doc.getObject("LightingAnalysis"), len(luminaires)

    @needs_solver
    def test_inputs_reach_the_page_and_survive_save_and_reopen(self):
        from lighting.solver import store

        folder = work_dir("report-inputs")
        doc, analysis, count = self._office_with_power(folder)
        scene_sha = _sha256(analysis.SceneFile)
        for name, value in INPUTS.items():
            setattr(analysis, name, value)
        # Report inputs are no part of the lighting model: the results stay current.
        self.assertEqual(store.results_state(analysis).state, "current")
        path = lighting.report(doc, os.path.join(folder, "inputs.html"))
        html = _read(path)
        self.assertEqual(_sha256(analysis.SceneFile), scene_sha)  # the traced scene untouched
        self.assertIn(f"<h1>{INPUTS['ProjectName']}</h1>", html)
        for row in ("<th>Project no.</th><td>2026-014</td>", "<th>Client</th><td>Müller AG</td>"):
            self.assertIn(row, html)
        for caption, who in (("Prepared by", "A. Architect"), ("Checked by", "K. Checker"),
                             ("Project", INPUTS["ProjectName"])):
            self.assertIn(f"<tr><th>{caption}</th><td>{who}</td></tr>", html)
        self.assertIn("2026-02-03", html)
        # LENI by EN 15193-1's formula from the inputs and 36 W per luminaire (the IES file).
        power = 36.0 * count
        lighting_kwh = power * 0.95 * 0.9 * (2000.0 * 0.8 + 400.0) / 1000.0
        leni = (lighting_kwh + 1.5 * 15.0) / 15.0
        from lighting.reporting import report_module

        fmt = report_module().fmt
        self.assertIn(f"<strong>{fmt.number(leni, 3)} kWh/(m²·a)</strong> over "
                      f"{fmt.number(15.0, 4)} m² (floor area as stated)", html)
        # Saved and reopened: the same inputs, the same page.
        saved = os.path.join(folder, "office.FCStd")
        doc.saveAs(saved)
        FreeCAD.closeDocument(doc.Name)
        doc = FreeCAD.openDocument(saved)
        analysis = doc.getObject("LightingAnalysis")
        for name, value in INPUTS.items():
            self.assertEqual(getattr(analysis, name), value, name)
        again = lighting.report(doc, os.path.join(folder, "reopened.html"))
        self.assertEqual(_read(again), html)

    @needs_solver
    def test_unusable_inputs_are_refused_by_property_name(self):
        folder = work_dir("report-inputs-bad")
        doc, analysis, _ = self._office_with_power(folder)
        before = sorted(os.listdir(folder))
        for name, value, said in (("OccupancyFactor", 1.5, "OccupancyFactor"),
                                  ("OperatingHoursNight", 8000.0, "exceed the 8760 hours"),
                                  ("FixedDate", "next week", "FixedDate")):
            for key, good in INPUTS.items():
                setattr(analysis, key, good)
            setattr(analysis, name, value)
            with self.assertRaises(LightingError) as caught:
                lighting.report(doc, os.path.join(folder, "bad.html"))
            self.assertIn(said, str(caught.exception))
            self.assertEqual(sorted(os.listdir(folder)), before)  # nothing written
        # Energy off: its inputs are not used, so not judged.
        analysis.FixedDate = "2026-02-03"
        analysis.EnergyEstimate = False
        html = _read(lighting.report(doc, os.path.join(folder, "no energy.html")))
        self.assertNotIn("Energy estimate", html)

    @needs_solver
    def test_the_date_of_the_calculation(self):
        from lighting.objects import results as results_obj
        from lighting.solver import store

        folder = work_dir("report-date")
        doc = build_office(photons=20000, seed=3)
        lighting.analyze(doc, output_dir=folder)
        analysis = doc.getObject("LightingAnalysis")
        obj = store.results_object(analysis)
        data = results_obj.traced(obj)
        # The run's end as stored (apply_to_document would keep the stored results: they
        # differ in a run fact only).
        data["provenance"]["finished_utc"] = "2025-03-04T23:59:58Z"
        obj.ResultsJson = json.dumps(data)
        self.assertEqual(store.results_state(analysis).state, "current")
        analysis.ReportDate = "Calculation"
        html = _read(lighting.report(doc, os.path.join(folder, "dated.html")))
        self.assertTrue('<td class="date">2025-03-04</td>' in html, "not the run's date")
        # An explicit date wins over the policy.
        html = _read(lighting.report(doc, os.path.join(folder, "given.html"), date=DATE))
        self.assertTrue(f'<td class="date">{DATE}</td>' in html, "not the date given")


class ReportLightScenes(DocTestCase):
    @needs_solver
    def test_traced_results_and_every_light_scene_whatever_is_shown(self):
        """The report gets the traced results, not the light scene the view shows, and a
        table for every light scene the document has now, also one made after the run."""
        import lightsolver
        from lighting.objects import results as results_obj
        from lighting.reporting import prepare_report, report_module

        fmt = report_module().fmt
        doc = build_office(photons=20000, seed=3)
        for name, group in (("Luminaire01", "Window row"), ("Luminaire02", "Window row"),
                            ("Luminaire03", "Back row"), ("Luminaire04", "Back row")):
            doc.getObject(name).ControlGroup = group
        analysis = doc.getObject("LightingAnalysis")
        analysis.Decide = False
        evening = lighting.make_light_scene(analysis, "Evening",
                                            {"Window row": 0.5, "Back row": 0.0})
        doc.recompute()
        folder = work_dir("report-scenes")
        lighting.analyze(doc, output_dir=folder)
        # Made after the run: not in the scene file the run wrote.
        lighting.make_light_scene(analysis, "Night", {"Window row": 0.0, "Back row": 0.25})
        lighting.show_light_scene(analysis, evening)  # the 3D view shows the evening
        obj = results_obj.of_analysis(analysis)
        traced = results_obj.traced(obj)
        shown = results_obj.data(obj)
        em = {t["name"]: t["mean_lux"] for t in traced["targets"]}
        dimmed = {t["name"]: t["mean_lux"] for t in shown["targets"]}
        self.assertNotEqual(fmt.lux(em["Workplane"]), fmt.lux(dimmed["Workplane"]))

        job = prepare_report(analysis, os.path.join(folder, "scenes.html"), date=DATE)
        self.assertEqual({k: v for k, v in job.data.items() if k != "warnings"},
                         {k: v for k, v in traced.items() if k != "warnings"})
        self.assertEqual([s["name"] for s in job.metadata["light_scenes"]], ["Evening", "Night"])
        html = _read(job.write())
        self.assertNotIn("Results shown", html)  # the cover: results as traced
        glance = html[html.index("Results at a glance"):]
        self.assertIn(fmt.lux(em["Workplane"]), glance[:glance.index("</table>")])
        for name, levels in (("Evening", {"Window row": 0.5, "Back row": 0.0}),
                             ("Night", {"Window row": 0.0, "Back row": 0.25})):
            self.assertIn(f"<h3>{name}</h3>", html)
            section = html[html.index(f"<h3>{name}</h3>"):]
            table = section[:section.index("</table>")]
            self.assertNotIn("Not shown", table)
            rescaled = lightsolver.rescale(traced, levels)
            workplane = next(t for t in rescaled["targets"] if t["name"] == "Workplane")
            self.assertIn(fmt.lux(workplane["mean_lux"]), table)
        # The view still shows the evening: writing the report changed nothing.
        self.assertIs(analysis.ActiveLightScene, evening)
