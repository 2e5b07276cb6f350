"""GUI scenario: the Report command and its panel (issue 13 item 5, issue 24 items 2, 4, 5).

From the Start page the user runs Examples/office.py as the Macro dialog does (built, not
solved; LIGHTING_BUILD_ONLY): the office in the Lighting workbench. Report sits in the analysis
toolbar after Results and is inactive without results. The luminaires get the batwing panel's
photometric file (as the chooser's Assign does: 36 W each from the file). After Run analysis
Report is active and opens the report panel in the combo view: the user types the project
number, client, prepared by, checked by and the operating hours with a presence control factor,
sets the report file and presses *Write report* (screenshot): the inputs are saved on the
analysis in one undo step and the PDF is written on a worker thread; a heartbeat timer shows
the event loop never waits long meanwhile (it froze 4.4 s before), the status bar says it is
writing, then the file written. The report got a picture of the 3D view in false colours (kept
as report_view.png). The PDF's text (pdftotext) holds the targets and their Em, the names
typed, the hours and the LENI that follows from them; its cover, picture, energy and sign-off
pages are rendered to PNG (docs/images/report-gui-*.png with --update-docs). The panel opened
again shows the saved inputs. Then a luminaire's flux is changed: Report asks (stubbed:
ask_what_to_do) and "Write marked stale" writes a report that says so; "Run analysis again"
runs the analysis and then writes a current report."""
import os
import shutil
import subprocess
import time

from guilib import (OUT, STATUS, expect, fits_width, grab_window, log, main_window, pump,
                    run_macro_file, scenario, visible_in_window, wait_until)

PHOTONS = 50000
#: What the user types into the report panel (field -> text), and the energy inputs.
TYPED = {"ProjectName": "Office refurbishment, 3rd floor", "ProjectNumber": "2026-014", "Client": "Müller Immobilien AG",
         "PreparedBy": "A. Architect, Studio Licht", "CheckedBy": "K. Checker"}
HOURS = {"OperatingHoursDay": 2750.0, "OperatingHoursNight": 250.0, "OccupancyFactor": 0.9}
#: PDF pages kept as pictures for the docs: heading found by pdftotext -> docs name.
DOCS_PAGES = (("Compliance", "report-gui-cover.png"),
              ("Energy estimate (LENI", "report-gui-energy.png"),
              ("The model in the 3D view", "report-gui-model.png"),
              ("Provenance and sign-off", "report-gui-signoff.png"))
EXAMPLE = os.path.join(os.environ.get("LIGHTING_SOURCE_DIR", "."), "Examples", "office.py")
#: The longest the event loop may wait while the report is written (it froze 4.4 s before).
MAX_GAP_S = 1.0


def open_example_by_macro() -> str:
    """Examples/office.py run as the Macro dialog runs it: the office built (not solved), saved,
    shown in the Lighting workbench; returns the file."""
    out = os.path.join(OUT, "office.FCStd")
    os.environ.update(LIGHTING_OUT=out, LIGHTING_BUILD_ONLY="1", LIGHTING_PHOTONS=str(PHOTONS))
    run_macro_file(EXAMPLE)
    pump(1.0)
    return out


def toolbar_actions(title: str) -> list:
    from PySide import QtGui

    for bar in main_window().findChildren(QtGui.QToolBar):
        if bar.windowTitle() == title:
            return [a.text() for a in bar.actions()]
    return []


def check_ugr_table(pdf: str, text: str, table) -> None:
    """The PDF holds the file's UGR table (its 4H x 8H row as the chooser shows it); its page
    is kept as an image to look at."""
    from guilib import OUT
    from lighting import luminaire_library as library

    expect(table is not None, "no UGR table for batwing_panel.ldt")
    expect("UGR table:" in text and "Viewed crosswise" in text, "no UGR table in the PDF")
    if table is None:
        return
    rows, x = library.ugr_table_texts(table), ""
    for row in rows:
        x = row[0] or x
        if (x, row[1]) == ("4H", "8H"):
            line = " ".join(row[1:7])  # Y and the five crosswise values, as pdftotext lays out
            STATUS["ugr_4h8h_line"] = line
            expect(" ".join(line.split()) in " ".join(text.split()),
                   f"4H x 8H row {line!r} not in the PDF text")
    page = next((i + 1 for i, p in enumerate(text.split("\f")) if "UGR table:" in p), None)
    if page:
        subprocess.run(["pdftoppm", "-r", "80", "-png", "-f", str(page), "-l", str(page), pdf,
                        os.path.join(OUT, "report_ugr_page")], check=False)
        STATUS["ugr_page"] = page


class Heartbeat:
    """A 20 ms timer on the GUI thread: the longest gap between its beats is how long the event
    loop could not run (a frozen GUI)."""

    def __init__(self) -> None:
        from PySide import QtCore

        self.beats = []
        self.timer = QtCore.QTimer()
        self.timer.setInterval(20)
        self.timer.timeout.connect(lambda: self.beats.append(time.monotonic()))

    def __enter__(self) -> "Heartbeat":
        self.timer.start()
        return self

    def __exit__(self, *exc) -> None:
        self.timer.stop()

    def gaps(self, skip=()) -> list:
        """(start, length) of each gap between beats, leaving out those that overlap a
        ``skip`` interval (the scenario's own work on the GUI thread, e.g. a screenshot)."""
        out = []
        for a, b in zip(self.beats, self.beats[1:]):
            if not any(a < end and b > begin for begin, end in skip):
                out.append((a, b - a))
        return out

    def max_gap(self, skip=()) -> float:
        gaps = self.gaps(skip)
        return max(g for _, g in gaps) if gaps else float("inf")


def keep_view_picture(report_cmd) -> None:
    """Keep a copy of the first 3D-view picture the command passes to a report (it deletes its
    temporary file once the report is written)."""
    taken = report_cmd.view_picture

    def view_picture():
        path = taken()
        STATUS.setdefault("view_png_given", path is not None)
        if path and "report_view" not in STATUS["images"]:
            shutil.copyfile(path, os.path.join(OUT, "report_view.png"))
            STATUS["images"]["report_view"] = os.path.join(OUT, "report_view.png")
        return path
    report_cmd.view_picture = view_picture


def type_into(widget, text: str) -> None:
    """Type ``text`` into a line edit or spin box as a user does: focus, select all, keys."""
    from PySide import QtCore, QtGui

    widget.setFocus()
    line = widget if isinstance(widget, QtGui.QLineEdit) else widget.lineEdit()
    line.selectAll()
    for char in text:
        for kind in (QtCore.QEvent.KeyPress, QtCore.QEvent.KeyRelease):
            QtGui.QApplication.sendEvent(line, QtGui.QKeyEvent(kind, 0, QtCore.Qt.NoModifier,
                                                               char))
    if not isinstance(widget, QtGui.QLineEdit):
        widget.interpretText()
    pump(0.05)


def write_button():
    """The task dialog's OK button, which the report panel calls "Write report"."""
    from PySide import QtGui

    for box in main_window().findChildren(QtGui.QDialogButtonBox):
        button = box.button(QtGui.QDialogButtonBox.Ok)
        if button is not None and button.isVisible():
            return button
    return None


def open_report_panel():
    """The Report command as the toolbar runs it: the report panel in the combo view."""
    import FreeCADGui

    from lighting.taskpanels import report_panel

    before = report_panel.last_panel()
    FreeCADGui.runCommand("Lighting_Report")
    pump(0.5)
    panel = report_panel.last_panel()
    expect(panel is not None and panel is not before, "Report opened no report panel")
    return panel


def fill_panel(panel, out: str) -> None:
    """The user's inputs: names typed, energy estimate ticked, hours and factor typed, the
    report file typed."""
    for name, text in TYPED.items():
        type_into(panel.texts[name], text)
    panel.energy.click()
    expect(panel.energy.isChecked() and panel.numbers["OperatingHoursDay"].isEnabled(),
           "ticking the energy estimate did not enable its fields")
    for name, value in HOURS.items():
        type_into(panel.numbers[name], f"{value:g}")
    type_into(panel.path, out)
    STATUS["panel_values"] = {k: v for k, v in panel.values().items()}


def write_first_report(report_cmd, out: str) -> None:
    """The Report command, its panel filled in, *Write report*: written on a worker thread
    while the GUI keeps running."""
    from lighting.taskpanels import sync

    panel = open_report_panel()
    if panel is None:
        return
    expect(sync.is_shown(panel), "the report panel is not in the task view")
    fill_panel(panel, out)
    button = write_button()
    expect(button is not None and button.text() == "Write report" and
           visible_in_window(button), f"no visible 'Write report' button: {button}")
    STATUS["panel_width"] = [panel.form.width(), panel.form.minimumSizeHint().width()]
    expect(fits_width(panel.form), f"the report panel is wider than the combo view "
                                   f"(width, minimum): {STATUS['panel_width']}")
    grab_window("report_panel", "report-gui-panel.png")
    with Heartbeat() as beat:
        started = time.monotonic()
        button.click()  # accept(): inputs saved, panel closed, writer started
        returned = time.monotonic() - started
        STATUS["command_returned_s"] = round(returned, 3)
        writer = report_cmd.last_writer()
        expect(writer is not None and not writer.finished,
               "Write report did not start writing in the background")
        writing = main_window().statusBar().currentMessage()
        STATUS["status_while_writing"] = writing
        expect("writing the report" in writing, f"status bar while writing: {writing!r}")
        grabbed = time.monotonic()
        grab_window("report_writing")  # the GUI while the report is written
        grab = (grabbed, time.monotonic())  # the scenario's own work on the GUI thread
        ok = wait_until(lambda: writer is not None and writer.finished, 180)
    STATUS["report_seconds"] = writer.seconds if writer else None
    STATUS["heartbeats"] = len(beat.beats)
    STATUS["screenshot_s"] = round(grab[1] - grab[0], 3)
    gap = beat.max_gap([(started, started + returned), grab])
    STATUS["max_gap_s"] = round(gap, 3)
    STATUS["longest_gaps"] = [(round(t - started, 2), round(g, 3)) for t, g in
                              sorted(beat.gaps(), key=lambda x: -x[1])[:5]]
    expect(ok and writer.job.error is None, f"the report was not written: "
                                             f"{writer.job.error if writer else None}")
    # Write report takes the 3D view's picture on the GUI thread (saveImage renders
    # offscreen; software OpenGL under Xvfb is slow), then returns.
    expect(returned < 2 * MAX_GAP_S, f"Write report blocked the GUI for {returned:.1f} s")
    expect(len(beat.beats) > 10 and gap < MAX_GAP_S,
           f"the event loop stalled while the report was written: {gap:.2f} s")
    expect(STATUS.get("view_png_given") is True, "the report got no picture of the 3D view")
    grab_window("report_written")


def check_inputs_saved(doc, analysis) -> None:
    """The inputs are the analysis' properties, saved in one undo step, shown again by the
    panel."""
    import FreeCADGui

    saved = {name: getattr(analysis, name) for name in list(TYPED) + list(HOURS)}
    STATUS["saved_inputs"] = saved
    expect(all(saved[name] == text for name, text in TYPED.items()) and
           all(abs(saved[name] - value) < 1e-9 for name, value in HOURS.items()) and
           analysis.EnergyEstimate, f"the panel's inputs are not on the analysis: {saved}")
    undo = list(doc.UndoNames)
    STATUS["undo_names"] = undo[:3]
    expect(undo[:1] == ["Report settings"], f"no 'Report settings' undo step: {undo[:3]}")
    panel = open_report_panel()
    if panel is not None:
        shown = {name: panel.texts[name].text() for name in TYPED}
        expect(shown == TYPED, f"the panel opened again shows {shown}")
        expect(panel.energy.isChecked(), "the panel opened again has no energy estimate")
        FreeCADGui.Control.closeDialog()
        pump(0.3)


def check_pdf_inputs(out: str, text: str, doc) -> None:
    """The PDF says what the user typed: names, hours, the LENI they give; its pages that
    matter are kept as pictures."""
    from lighting.reporting import report_module

    flat = " ".join(text.split())
    for name, typed in TYPED.items():
        expect(typed in flat, f"{name} {typed!r} not in the PDF text")
    for part in ("Project no.", "2026-014", "Client", "Müller Immobilien AG"):
        expect(part in flat, f"{part!r} (project number and client rows) not in the PDF text")
    fmt = report_module().fmt
    hours = (f"= {fmt.number(HOURS['OperatingHoursDay'], 5)} h with daylight",
             f"= {fmt.number(HOURS['OperatingHoursNight'], 5)} h without")
    for part in hours:
        expect(" ".join(part.split()) in flat, f"{part!r} not in the PDF text")
    # LENI = P F_C F_O (t_D F_D + t_N) / 1000 / A, A the floor inside the office's walls (no
    # floor area given: the report measures it on the plan), the example's 5 m x 4 m room.
    import importlib.util
    model_py = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                            "Examples", "office_model.py")
    spec = importlib.util.spec_from_file_location("office_model_dimensions", model_py)
    office_model = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(office_model)
    area = office_model.ROOM_X_MM * office_model.ROOM_Y_MM / 1.0e6
    power = 36.0 * 4
    leni = power * HOURS["OccupancyFactor"] * (
        HOURS["OperatingHoursDay"] + HOURS["OperatingHoursNight"]) / 1000.0 / area
    STATUS["leni_expected"] = fmt.number(leni, 3)
    expect(f"{fmt.number(leni, 3)} kWh/(m²·a)" in flat, f"LENI {fmt.number(leni, 3)} not in "
                                                        "the PDF text")
    pages = text.split("\f")
    for heading, docs_name in DOCS_PAGES:
        page = next((i + 1 for i, p in enumerate(pages) if heading in p), None)
        expect(page is not None, f"no page with {heading!r}")
        if page is None:
            continue
        stem = os.path.join(OUT, docs_name[:-4])
        subprocess.run(["pdftoppm", "-r", "100", "-png", "-singlefile", "-f", str(page),
                        "-l", str(page), out, stem], check=False)
        key = docs_name[:-4].replace("-", "_")
        if os.path.exists(stem + ".png"):
            STATUS["images"][key] = stem + ".png"
            STATUS["docs_images"][key] = docs_name
        STATUS.setdefault("pdf_pages", {})[heading] = page


def write_from_panel(path: str) -> None:
    """Report, the file typed into the panel, Write report."""
    panel = open_report_panel()
    if panel is None:
        return
    type_into(panel.path, path)
    button = write_button()
    if expect(button is not None, "no Write report button"):
        button.click()


def stale_then_choices(doc, report_cmd, folder: str) -> None:
    """Stale results: the question, "Write marked stale", then "Run analysis again"."""
    import FreeCADGui

    asked = []
    luminaire = doc.getObject("Luminaire01")
    luminaire.FluxLumen = luminaire.FluxLumen * 1.5
    doc.recompute()
    pump(0.5)
    stale = os.path.join(folder, "stale report.html")
    report_cmd.ask_what_to_do = lambda problem, marked: asked.append((problem, marked)) or "write"
    write_from_panel(stale)
    STATUS["stale_question"] = asked[:1]
    expect(len(asked) == 1 and asked[0][1] == "stale" and "Luminaire01" in asked[0][0],
           f"no question about stale results: {asked}")
    ok = wait_until(lambda: os.path.exists(stale), 120)
    if expect(ok, "'Write marked stale' wrote no report"):
        with open(stale, encoding="utf-8") as stream:
            expect("results out of date (stale)" in stream.read(),
                   "the report written anyway does not say the results are stale")
    # "Run analysis again": the run, then the report of current results.
    again = os.path.join(folder, "after the run.html")
    report_cmd.ask_what_to_do = lambda problem, marked: asked.append((problem, marked)) or "run"
    write_from_panel(again)
    ok = wait_until(lambda: os.path.exists(again), 240)
    STATUS["questions"] = len(asked)
    if expect(ok, "'Run analysis again' wrote no report after the run"):
        with open(again, encoding="utf-8") as stream:
            expect("out of date" not in stream.read(), "the report after the run says stale")
    expect(len(asked) == 2, f"asked {len(asked)} times (expected 2): {asked}")
    FreeCADGui.Control.closeDialog()
    pump(0.5)


def body() -> None:
    import FreeCAD
    import FreeCADGui

    from lighting.commands import report as report_cmd
    from lighting.taskpanels import analysis_panel

    expect(STATUS["start_workbench"] == "StartWorkbench" and FreeCAD.ActiveDocument is None,
           "FreeCAD did not start on the Start page without a document")
    path = open_example_by_macro()
    doc = FreeCAD.ActiveDocument
    expect(doc is not None and doc.FileName == path, f"the example is not open: {doc}")
    expect(FreeCADGui.activeWorkbench().name() == "LightingWorkbench",
           "the example did not end in the Lighting workbench")
    actions = toolbar_actions("Lighting analysis")
    STATUS["toolbar"] = actions
    expect("Report" in actions and actions.index("Report") == actions.index("Results") + 1,
           f"Report is not after Results in the analysis toolbar: {actions}")
    expect(not report_cmd.CommandReport().IsActive(), "Report is active before any results")
    # One luminaire photometric (as the chooser's Assign does): the report prints its file's
    # full UGR table.
    import lighting
    from lighting import luminaire_library as library

    ldt = os.path.join(os.environ["LIGHTING_SOURCE_DIR"], "Resources", "luminaires",
                       "batwing_panel.ldt")
    lighting.assign_photometry(doc, [doc.getObject(f"Luminaire0{i}") for i in range(1, 5)], ldt)

    FreeCADGui.runCommand("Lighting_Run")
    wait_until(lambda: analysis_panel.last_run() is not None and
               analysis_panel.last_run().stage in ("done", "failed", "cancelled"), 180)
    job = analysis_panel.last_run()
    expect(job is not None and job.stage == "done", f"the run did not finish: {job}")
    FreeCADGui.Control.closeDialog()
    pump(0.5)
    expect(report_cmd.CommandReport().IsActive(), "Report is not active after the run")
    analysis = doc.getObject("LightingAnalysis")
    expect(report_cmd.default_path(analysis) ==
           os.path.join(os.path.dirname(path), f"{doc.Label} lighting report.pdf"),
           f"default report path {report_cmd.default_path(analysis)!r}")

    out = os.path.join(os.path.dirname(path), "office report.pdf")
    keep_view_picture(report_cmd)
    write_first_report(report_cmd, out)
    check_inputs_saved(doc, analysis)
    ok = os.path.exists(out)
    expect(ok, "no report written")
    if ok:
        with open(out, "rb") as stream:
            expect(stream.read(5) == b"%PDF-", "the report is not a PDF")
        text = subprocess.run(["pdftotext", "-layout", out, "-"], capture_output=True,
                              text=True).stdout
        STATUS["pdf_text_head"] = text[:400]
        results = lighting.results(doc)
        from lighting.reporting import report_module

        fmt = report_module().fmt
        for target in results.targets:
            expect(target.label in text and fmt.lux(target.mean_lux) in text,
                   f"{target.label} Em {fmt.lux(target.mean_lux)} not in the PDF text")
        check_ugr_table(out, text, library.ugr_table(ldt))
        check_pdf_inputs(out, text, doc)
    message = main_window().statusBar().currentMessage()
    STATUS["status_bar"] = message
    log(f"status bar: {message}")
    expect("report written to" in message, f"status bar after the report: {message!r}")
    stale_then_choices(doc, report_cmd, os.path.dirname(path))


scenario(body)
