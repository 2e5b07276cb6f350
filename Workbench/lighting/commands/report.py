# SPDX-License-Identifier: LGPL-2.1-or-later
"""Command "Report": writes the calculation report of the analysis' stored results as PDF or
HTML (``lighting.report``, docs/report.md). commands.register() adds it; RUN_COMMANDS places it
after Results. It opens the report panel (taskpanels/report_panel.py): the report's inputs
(project, sign-off names, date, energy; saved on the analysis) and the file; *Write report*
then writes it as below.

The report takes seconds (WeasyPrint), so it is written on a worker thread that a QTimer
polls, as the analysis panel does for a run (solver/machine.py): the document is read first on
the GUI thread (``reporting.prepare_report``, with a picture of the 3D view), the worker then
touches only files. Stale or partial results are not reported silently: the user chooses to
run the analysis again (the report follows when it is done) or to write it marked as such."""
from __future__ import annotations

import os
import tempfile
import time
from typing import Any, Callable, List, Optional

import FreeCAD
import FreeCADGui

from lighting.commands import commands as _commands

NAME = "Lighting_Report"
FILTER = "PDF report (*.pdf);;HTML report (*.html)"
POLL_MS = 100
#: The picture of the 3D view in the report, in pixels (4:3). Coin draws the legend's text at a
#: fixed pixel size: at 1200 px across the page's 170 mm it prints at about 5.5 pt (at 1600 px
#: it was too small to read), and the picture stays sharp enough (180 dpi).
VIEW_SIZE = (1200, 900)
#: How long to wait for Run analysis to start its run before giving up on the report.
RUN_START_S = 5.0

_writers: List[Any] = []  # writers and runs alive while their timers poll
_last_writer: Optional["ReportWriter"] = None


def last_writer() -> Optional["ReportWriter"]:
    """The last report started from the GUI (tests poll it)."""
    return _last_writer


def default_path(analysis: Any) -> str:
    """``<document> lighting report.pdf`` beside the saved document, else in the home folder."""
    doc = analysis.Document
    folder = os.path.dirname(doc.FileName) if doc.FileName else os.path.expanduser("~")
    return os.path.join(folder, f"{doc.Label} lighting report.pdf")


def ask_path(analysis: Any) -> Optional[str]:
    """The file the user chooses (``.pdf`` added when the name has no known suffix), or None."""
    from PySide import QtGui

    start = str(getattr(analysis, "ReportFile", "") or "") or default_path(analysis)
    path, chosen = QtGui.QFileDialog.getSaveFileName(
        FreeCADGui.getMainWindow(), "Write the lighting report", start, FILTER)
    if not path:
        return None
    if os.path.splitext(path)[1].lower() not in (".pdf", ".html", ".htm"):
        path += ".html" if "html" in (chosen or "") else ".pdf"
    return path


def ask_what_to_do(problem: str, marked: str) -> str:
    """Stale or partial results: "run" (the analysis again, then the report), "write" (marked
    ``marked``) or "cancel". Tests replace this function (the user's click)."""
    from PySide import QtGui

    box = QtGui.QMessageBox(FreeCADGui.getMainWindow())
    box.setIcon(QtGui.QMessageBox.Warning)
    box.setWindowTitle("Lighting report")
    box.setText(problem)
    box.setInformativeText("A report is signed: run the analysis again so that it describes "
                           f"the model, or write it now, marked {marked} on its pages.")
    run = box.addButton("Run analysis again", QtGui.QMessageBox.AcceptRole)
    write = box.addButton(f"Write marked {marked}", QtGui.QMessageBox.DestructiveRole)
    box.addButton(QtGui.QMessageBox.Cancel)
    box.setDefaultButton(run)
    box.exec_()
    clicked = box.clickedButton()
    return "run" if clicked is run else "write" if clicked is write else "cancel"


def view_picture() -> Optional[str]:
    """The active 3D view as the user sees it (false colours and legend) in a temporary PNG,
    taken on the GUI thread; None without a 3D view (the report then draws its own)."""
    gui_doc = FreeCADGui.ActiveDocument
    view = getattr(gui_doc, "ActiveView", None) if gui_doc is not None else None
    if view is None or not hasattr(view, "saveImage"):
        return None
    handle, path = tempfile.mkstemp(prefix="lighting-view-", suffix=".png")
    os.close(handle)
    try:
        view.saveImage(path, VIEW_SIZE[0], VIEW_SIZE[1], "White")
        if os.path.getsize(path) > 0:
            return path
    except Exception as exc:  # noqa: BLE001 - a report without the picture is still a report
        FreeCAD.Console.PrintWarning(f"Lighting: no picture of the 3D view for the report: "
                                     f"{exc}\n")
    os.unlink(path)
    return None


def _status(text: str, ms: int = 8000) -> None:
    FreeCADGui.getMainWindow().statusBar().showMessage(text, ms)


def _failed(text: str) -> None:
    from PySide import QtGui

    FreeCAD.Console.PrintError(f"Lighting: report failed: {text}\n")
    _status("Lighting: the report was not written")
    QtGui.QMessageBox.warning(FreeCADGui.getMainWindow(), "Lighting",
                              f"The report could not be written:\n{text}")


class ReportWriter:
    """One report written on a worker thread (``ReportJob.start``) while a QTimer on the GUI
    thread polls it; the end is said in the console, the status bar or a message box."""

    def __init__(self, job: Any, picture: Optional[str]) -> None:
        from PySide import QtCore

        self.job = job
        self.picture = picture
        self.started = time.monotonic()
        self.seconds: Optional[float] = None
        self.timer = QtCore.QTimer()
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self._poll)

    @property
    def finished(self) -> bool:
        return self.seconds is not None

    def start(self) -> None:
        global _last_writer
        _last_writer = self
        _writers.append(self)
        FreeCAD.Console.PrintMessage(
            f"Lighting: writing the report in the background: lighting.report("
            f"FreeCAD.ActiveDocument, {self.job.path!r})\n")
        _status(f"Lighting: writing the report {os.path.basename(self.job.path)}...", 0)
        self.job.start()
        self.timer.start()

    def _poll(self) -> None:
        if not self.job.finished:
            return
        self.timer.stop()
        self.seconds = time.monotonic() - self.started
        if self in _writers:
            _writers.remove(self)
        if self.picture:
            try:
                os.unlink(self.picture)
            except OSError:
                pass
        if self.job.error is not None:
            error = self.job.error
            _failed(str(error) if isinstance(error, Exception) else repr(error))
            return
        FreeCAD.Console.PrintMessage(f"Lighting: report written to {self.job.written} "
                                     f"({self.seconds:.1f} s)\n")
        _status(f"Lighting: report written to {self.job.written}")


def write_report(analysis: Any, path: str, allow_stale: bool = False,
                 allow_partial: bool = False) -> Optional[ReportWriter]:
    """Start writing the report of ``analysis`` to ``path``; returns the writer (poll its
    ``finished``), or None when nothing is written (refused, cancelled, or the analysis is run
    again first: the report then follows the run)."""
    from lighting import reporting

    try:
        job = reporting.prepare_report(analysis, path, allow_stale=allow_stale,
                                       allow_partial=allow_partial)
    except reporting.StaleResultsError as exc:
        return _choose(analysis, path, str(exc), "stale",
                       lambda: write_report(analysis, path, True, allow_partial))
    except reporting.PartialResultsError as exc:
        return _choose(analysis, path, str(exc), "partial",
                       lambda: write_report(analysis, path, allow_stale, True))
    except Exception as exc:  # noqa: BLE001 - the message says what is missing or wrong
        _failed(str(exc))
        return None
    job.view_png = view_picture()
    writer = ReportWriter(job, job.view_png)
    writer.start()
    return writer


def _choose(analysis: Any, path: str, problem: str, marked: str,
            anyway: Callable[[], Optional[ReportWriter]]) -> Optional[ReportWriter]:
    choice = ask_what_to_do(problem, marked)
    if choice == "write":
        return anyway()
    if choice == "run":
        RunThenReport(analysis, path).start()
    else:
        _status("Lighting: the report was not written")
    return None


class RunThenReport:
    """Run analysis (its command and panel, as the user would), then write the report once
    the run is done; a failed or cancelled run writes nothing (a cancelled one asks again)."""

    def __init__(self, analysis: Any, path: str) -> None:
        from PySide import QtCore

        from lighting.taskpanels import analysis_panel

        self.analysis, self.path = analysis, path
        self.before = analysis_panel.last_run()
        self.asked = time.monotonic()
        self.timer = QtCore.QTimer()
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self._poll)

    def start(self) -> None:
        _writers.append(self)
        FreeCADGui.runCommand("Lighting_Run")
        _status("Lighting: running the analysis; the report follows", 0)
        self.timer.start()

    def _stop(self) -> None:
        self.timer.stop()
        if self in _writers:
            _writers.remove(self)

    def _poll(self) -> None:
        from lighting.taskpanels import analysis_panel

        job = analysis_panel.last_run()
        if job is None or job is self.before:
            if time.monotonic() - self.asked > RUN_START_S:
                self._stop()
                _status("Lighting: the analysis did not start; the report was not written")
            return
        if job.stage not in ("done", "failed", "cancelled"):
            return
        self._stop()
        if job.stage == "failed":
            _status("Lighting: the analysis failed; the report was not written")
            return
        write_report(self.analysis, self.path)


def _has_results(analysis: Optional[Any]) -> bool:
    if analysis is None:
        return False
    from lighting.objects import results

    return results.of_analysis(analysis) is not None


class CommandReport(_commands.BaseCommand):
    NAME, ICON = NAME, "Lighting_Results"
    MENU = "Report"
    TIP = ("Write the calculation report (PDF or HTML): luminaires, surfaces, Em, Emin, U0 "
           "with their intervals, the requirements' verdicts, false-colour plans")

    def IsActive(self) -> bool:  # noqa: N802 (FreeCAD API name)
        return _commands._doc() is not None and _has_results(_commands.active_analysis())

    def Activated(self) -> None:  # noqa: N802
        open_panel(_commands.active_analysis())


def open_panel(analysis: Any) -> Optional[Any]:
    """The report panel of ``analysis`` in the task view (after closing the open Lighting
    panel, unless it is running: then None and the user is told why)."""
    from lighting.taskpanels import report_panel, sync

    if not sync.close_current():
        return None
    # ask_path and write_report are looked up when called: tests replace them (the user's
    # answer in the save dialog).
    panel = report_panel.ReportTaskPanel(
        analysis, write=lambda a, path: write_report(a, path),
        ask_path=lambda a: ask_path(a), default_path=default_path(analysis))
    return sync.show(panel)
