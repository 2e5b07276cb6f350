# SPDX-License-Identifier: LGPL-2.1-or-later
"""Command "Report": writes the calculation report of the analysis' stored results as PDF or
HTML (``lighting.report``, docs/report.md), asking where. commands.register() adds it;
RUN_COMMANDS places it after Results."""
from __future__ import annotations

import os
from typing import Any, Optional

import FreeCAD
import FreeCADGui

from lighting.commands import commands as _commands

NAME = "Lighting_Report"
FILTER = "PDF report (*.pdf);;HTML report (*.html)"


def default_path(analysis: Any) -> str:
    """``<document> lighting report.pdf`` beside the saved document, else in the home folder."""
    doc = analysis.Document
    folder = os.path.dirname(doc.FileName) if doc.FileName else os.path.expanduser("~")
    return os.path.join(folder, f"{doc.Label} lighting report.pdf")


def ask_path(analysis: Any) -> Optional[str]:
    """The file the user chooses (``.pdf`` added when the name has no known suffix), or None."""
    from PySide import QtGui

    path, chosen = QtGui.QFileDialog.getSaveFileName(
        FreeCADGui.getMainWindow(), "Write the lighting report", default_path(analysis), FILTER)
    if not path:
        return None
    if os.path.splitext(path)[1].lower() not in (".pdf", ".html", ".htm"):
        path += ".html" if "html" in (chosen or "") else ".pdf"
    return path


def write_report(analysis: Any, path: str) -> Optional[str]:
    """Write the report as the Python console would (the line is echoed there); errors are
    shown in a message box. Returns the path written, or None."""
    from PySide import QtCore, QtGui

    FreeCADGui.addModule("lighting")
    QtGui.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)  # WeasyPrint takes seconds
    try:
        FreeCADGui.doCommand(f"lighting.report(FreeCAD.ActiveDocument, {path!r}, "
                             f"analysis=FreeCAD.ActiveDocument.getObject('{analysis.Name}'))")
    except Exception as exc:  # noqa: BLE001 - the message says what is missing or wrong
        QtGui.QApplication.restoreOverrideCursor()
        FreeCAD.Console.PrintError(f"Lighting: report failed: {exc}\n")
        QtGui.QMessageBox.warning(FreeCADGui.getMainWindow(), "Lighting",
                                  f"The report could not be written:\n{exc}")
        return None
    QtGui.QApplication.restoreOverrideCursor()
    FreeCAD.Console.PrintMessage(f"Lighting: report written to {path}\n")
    FreeCADGui.getMainWindow().statusBar().showMessage(f"Lighting: report written to {path}",
                                                       8000)
    return path


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
        analysis = _commands.active_analysis()
        path = ask_path(analysis)
        if path:
            write_report(analysis, path)
