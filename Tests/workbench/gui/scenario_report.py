"""GUI scenario: the Report command (issue 13 item 5, issue 24 items 2 and 5).

From the Start page the user runs Examples/office.py as the Macro dialog does (built, not
solved; LIGHTING_BUILD_ONLY): the office in the Lighting workbench. Report sits in the analysis
toolbar after Results and is inactive without results. After Run analysis it is active; the
user chooses a file name in the save dialog (stubbed: ask_path) and the PDF is written on a
worker thread: a heartbeat timer shows the event loop never waits long meanwhile (it froze
4.4 s before), the status bar says it is writing (screenshot), then the file written. The
report got a picture of the 3D view in false colours (kept as report_view.png). The PDF's text
holds the targets and their Em. Then a luminaire's flux is changed: Report asks (stubbed:
ask_what_to_do) and "Write marked stale" writes a report that says so; "Run analysis again"
runs the analysis and then writes a current report."""
import os
import shutil
import subprocess
import time

from guilib import (OUT, STATUS, expect, grab_window, log, main_window, pump, run_macro_file,
                    scenario, wait_until)

PHOTONS = 50000
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


def write_first_report(report_cmd, out: str) -> None:
    """The Report command with the save dialog's answer ``out``: written on a worker thread
    while the GUI keeps running."""
    import FreeCADGui

    with Heartbeat() as beat:
        started = time.monotonic()
        FreeCADGui.runCommand("Lighting_Report")
        returned = time.monotonic() - started
        STATUS["command_returned_s"] = round(returned, 3)
        writer = report_cmd.last_writer()
        expect(writer is not None and not writer.finished,
               "the Report command did not start writing in the background")
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
    # The command itself takes the 3D view's picture on the GUI thread (saveImage renders
    # offscreen; software OpenGL under Xvfb is slow), then returns.
    expect(returned < 2 * MAX_GAP_S, f"the Report command blocked the GUI for {returned:.1f} s")
    expect(len(beat.beats) > 10 and gap < MAX_GAP_S,
           f"the event loop stalled while the report was written: {gap:.2f} s")
    expect(STATUS.get("view_png_given") is True, "the report got no picture of the 3D view")
    grab_window("report_written")


def stale_then_choices(doc, report_cmd, folder: str) -> None:
    """Stale results: the question, "Write marked stale", then "Run analysis again"."""
    import FreeCADGui

    asked = []
    luminaire = doc.getObject("Luminaire01")
    luminaire.FluxLumen = luminaire.FluxLumen * 1.5
    doc.recompute()
    pump(0.5)
    stale = os.path.join(folder, "stale report.html")
    report_cmd.ask_path = lambda analysis: stale
    report_cmd.ask_what_to_do = lambda problem, marked: asked.append((problem, marked)) or "write"
    FreeCADGui.runCommand("Lighting_Report")
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
    report_cmd.ask_path = lambda analysis: again
    report_cmd.ask_what_to_do = lambda problem, marked: asked.append((problem, marked)) or "run"
    FreeCADGui.runCommand("Lighting_Report")
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
    lighting.assign_photometry(doc, [doc.getObject("Luminaire01")], ldt)

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
    report_cmd.ask_path = lambda analysis: out  # the user's choice in the save dialog
    keep_view_picture(report_cmd)
    write_first_report(report_cmd, out)
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
    message = main_window().statusBar().currentMessage()
    STATUS["status_bar"] = message
    log(f"status bar: {message}")
    expect("report written to" in message, f"status bar after the report: {message!r}")
    stale_then_choices(doc, report_cmd, os.path.dirname(path))


scenario(body)
