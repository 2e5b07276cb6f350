"""GUI scenario: the Report command (issue 13, item 5).

From the Start page the user opens the example office (built by Examples/office.py without
solving) in the Lighting workbench: Report sits in the analysis toolbar after Results and is
inactive without results. After Run analysis it is active; the user chooses a file name in the
save dialog (stubbed: ask_path) and gets the PDF, the console shows the equivalent
``lighting.report(...)`` line, the status bar the file written. The PDF's text holds the
targets and their Em."""
import os
import subprocess

from guilib import build_example_file, STATUS, expect, log, main_window, pump, scenario, wait_until

PHOTONS = 50000


def build_example() -> str:
    return build_example_file(PHOTONS)


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


def body() -> None:
    import FreeCAD
    import FreeCADGui

    from lighting.commands import report as report_cmd
    from lighting.taskpanels import analysis_panel

    path = build_example()
    FreeCADGui.activateWorkbench("LightingWorkbench")
    doc = FreeCAD.openDocument(path)
    pump(1.0)
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
    FreeCADGui.runCommand("Lighting_Report")
    ok = wait_until(lambda: os.path.exists(out), 120)
    expect(ok, "no report written")
    if ok:
        with open(out, "rb") as stream:
            expect(stream.read(5) == b"%PDF-", "the report is not a PDF")
        text = subprocess.run(["pdftotext", "-layout", out, "-"], capture_output=True,
                              text=True).stdout
        STATUS["pdf_text_head"] = text[:400]
        import lighting

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


scenario(body)
