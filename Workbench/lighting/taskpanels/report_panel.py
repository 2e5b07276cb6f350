# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel "Lighting report": the report's inputs and its file, opened by the Report
command (commands/report.py).

The user reviews and edits what the report says besides the results: the project (name,
number, client), who prepared and who checked it, its date, and the energy estimate's inputs
(LENI, EN 15193-1: operating hours, control factors, parasitic energy, the floor area); then
chooses the file. *Write report* saves the inputs on the analysis (its group "Report",
objects/report_settings.py; one undo step "Report settings", none when nothing changed),
closes the panel and writes the report on the command's worker thread, so the 3D view the
report pictures is the one the user sees. Fields are stacked (label above field), so the panel
fits FreeCAD's default combo view."""
from __future__ import annotations

import datetime
import os
from types import SimpleNamespace
from typing import Any, Callable, Dict, List, Optional

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from lighting.objects import light_scene, report_settings
from lighting.viewproviders.base import icon_path

#: ReportDate's items as the panel names them.
DATE_TEXTS = {"Today": "Today", "Calculation": "Day of the calculation",
              "Fixed": "Fixed date"}
TEXT_FIELDS = (("ProjectName", "Project name"), ("ProjectNumber", "Project number"),
               ("Client", "Client"), ("PreparedBy", "Prepared by"), ("CheckedBy", "Checked by"))
#: Energy property, label, suffix, maximum, decimals, step.
NUMBER_FIELDS = (
    ("OperatingHoursDay", "Hours in use with daylight (t_D)", " h/a", 8760.0, 0, 50.0),
    ("OperatingHoursNight", "Hours in use without daylight (t_N)", " h/a", 8760.0, 0, 50.0),
    ("OccupancyFactor", "Occupancy factor (F_O)", "", 1.0, 2, 0.05),
    ("DaylightDependencyFactor", "Daylight dependency factor (F_D)", "", 1.0, 2, 0.05),
    ("ConstantIlluminanceFactor", "Constant illuminance factor (F_C)", "", 1.0, 2, 0.05),
    ("ParasiticEnergy", "Parasitic energy", " kWh/(m² a)", 1.0e4, 2, 0.1),
    ("EnergyFloorArea", "Floor area (0: the largest work plane)", " m²", 1.0e5, 2, 1.0))

_last_panel: Optional["ReportTaskPanel"] = None


def last_panel() -> Optional["ReportTaskPanel"]:
    """The most recently opened panel (for the GUI scenarios)."""
    return _last_panel


def _form(parent: QtGui.QWidget) -> QtGui.QFormLayout:
    form = QtGui.QFormLayout(parent)
    # Label above field: the panel stays narrow enough for the default combo view.
    form.setRowWrapPolicy(QtGui.QFormLayout.WrapAllRows)
    form.setFieldGrowthPolicy(QtGui.QFormLayout.AllNonFixedFieldsGrow)
    return form


def _label(text: str) -> QtGui.QLabel:
    """A field's label that wraps rather than widen the panel."""
    label = QtGui.QLabel(text)
    label.setWordWrap(True)
    return label


class ReportTaskPanel:
    """FreeCAD task dialog (``form`` + accept/reject) for one analysis' report.

    ``write`` is called with (analysis, path) once the inputs are saved and the panel is
    closed: the command's ``write_report`` (worker thread, questions about stale results)."""

    def __init__(self, analysis: Any, write: Callable[[Any, str], Any],
                 ask_path: Callable[[Any], Optional[str]], default_path: str) -> None:
        global _last_panel
        _last_panel = self
        self.analysis = analysis
        self.write = write
        self.ask_path = ask_path
        self.form = QtGui.QWidget()
        self.form.setWindowTitle("Lighting report")
        self.form.setWindowIcon(QtGui.QIcon(icon_path("Lighting_Results")))
        self.texts: Dict[str, QtGui.QLineEdit] = {}
        self.numbers: Dict[str, QtGui.QDoubleSpinBox] = {}
        self.written: Optional[str] = None  # the path handed to ``write``
        outer = QtGui.QVBoxLayout(self.form)
        self.about = QtGui.QLabel(self._about_text())
        self.about.setWordWrap(True)
        outer.addWidget(self.about)
        outer.addWidget(self._project_box())
        outer.addWidget(self._signoff_box())
        outer.addWidget(self._energy_box())
        outer.addWidget(self._output_box(str(analysis.ReportFile or "") or default_path))
        outer.addStretch(1)
        self._policy_changed()
        self._energy_toggled()

    # -- widgets ---------------------------------------------------------------------------
    def _line(self, name: str) -> QtGui.QLineEdit:
        edit = QtGui.QLineEdit(str(getattr(self.analysis, name) or ""))
        edit.setToolTip(self.analysis.getDocumentationOfProperty(name))
        self.texts[name] = edit
        return edit

    def _project_box(self) -> QtGui.QGroupBox:
        box = QtGui.QGroupBox("Project")
        form = _form(box)
        for name, label in TEXT_FIELDS[:3]:
            form.addRow(_label(label), self._line(name))
        self.texts["ProjectName"].setPlaceholderText(self.analysis.Document.Label)
        return box

    def _signoff_box(self) -> QtGui.QGroupBox:
        from lighting.reporting import signoff_of

        box = QtGui.QGroupBox("Sign-off")
        form = _form(box)
        for name, label in TEXT_FIELDS[3:]:
            form.addRow(_label(label), self._line(name))
        author = signoff_of(self.analysis.Document).get("author", "")
        self.texts["PreparedBy"].setPlaceholderText(author or "name, company")
        self.texts["CheckedBy"].setPlaceholderText("blank: a line to sign on")
        self.policy = QtGui.QComboBox()
        self.policy.setSizeAdjustPolicy(
            QtGui.QComboBox.AdjustToMinimumContentsLengthWithIcon)
        self.policy.setMinimumContentsLength(8)
        for key in report_settings.DATE_POLICIES:
            self.policy.addItem(DATE_TEXTS[key], key)
        self.policy.setCurrentIndex(
            report_settings.DATE_POLICIES.index(self.analysis.ReportDate))
        self.policy.setToolTip(self.analysis.getDocumentationOfProperty("ReportDate"))
        self.policy.currentIndexChanged.connect(self._policy_changed)
        self.fixed = QtGui.QDateEdit()
        self.fixed.setDisplayFormat("yyyy-MM-dd")
        self.fixed.setCalendarPopup(True)
        try:
            day = datetime.date.fromisoformat(str(self.analysis.FixedDate))
        except ValueError:
            day = datetime.date.today()
        self.fixed.setDate(QtCore.QDate(day.year, day.month, day.day))
        form.addRow(_label("Date of the report"), self.policy)
        form.addRow(_label("Fixed date"), self.fixed)
        return box

    def _energy_box(self) -> QtGui.QGroupBox:
        box = QtGui.QGroupBox("Energy (LENI, EN 15193-1)")
        form = _form(box)
        self.energy = QtGui.QCheckBox("Estimate the energy use")
        self.energy.setChecked(bool(self.analysis.EnergyEstimate))
        self.energy.setToolTip(self.analysis.getDocumentationOfProperty("EnergyEstimate"))
        self.energy.toggled.connect(self._energy_toggled)
        form.addRow(self.energy)
        for name, label, suffix, top, decimals, step in NUMBER_FIELDS:
            spin = QtGui.QDoubleSpinBox()
            spin.setRange(0.0, top)
            spin.setDecimals(decimals)
            spin.setSingleStep(step)
            spin.setSuffix(suffix)
            spin.setValue(float(getattr(self.analysis, name)))
            spin.setToolTip(self.analysis.getDocumentationOfProperty(name))
            self.numbers[name] = spin
            form.addRow(_label(label), spin)
        self.numbers["EnergyFloorArea"].setSpecialValueText("largest work plane")
        return box

    def _output_box(self, path: str) -> QtGui.QGroupBox:
        box = QtGui.QGroupBox("Report file (PDF or HTML)")
        row = QtGui.QHBoxLayout(box)
        self.path = QtGui.QLineEdit(path)
        self.path.setToolTip("The file to write: .pdf or .html, in a folder that exists")
        browse = QtGui.QPushButton("...")
        browse.setToolTip("Choose the file")
        browse.setMaximumWidth(32)
        browse.clicked.connect(self._browse)
        row.addWidget(self.path, 1)
        row.addWidget(browse)
        return box

    def _about_text(self) -> str:
        """What the report will show: results as traced, a page per light scene, the picture."""
        scenes = light_scene.scenes(self.analysis)
        text = "The report shows the results as traced (every luminaire at 100 %)"
        if scenes:
            text += (f" and a page for each light scene ({', '.join(s.Label for s in scenes)})"
                     ", rescaled from the same run")
        text += ". Its picture of the model is the 3D view as it is when you write it"
        shown = light_scene.active(self.analysis)
        if shown is not None:
            text += f" (now showing the light scene {shown.Label})"
        return text + "."

    # -- reactions -------------------------------------------------------------------------
    def _policy_changed(self, *_: Any) -> None:
        self.fixed.setEnabled(self.policy.currentData() == "Fixed")

    def _energy_toggled(self, *_: Any) -> None:
        for spin in self.numbers.values():
            spin.setEnabled(self.energy.isChecked())

    def _browse(self) -> None:
        chosen = self.ask_path(self.analysis)
        if chosen:
            self.path.setText(chosen)

    # -- the values ------------------------------------------------------------------------
    def values(self) -> Dict[str, Any]:
        """The panel's fields by property name, as they would be saved."""
        out: Dict[str, Any] = {name: edit.text().strip() for name, edit in self.texts.items()}
        out["ReportDate"] = self.policy.currentData()
        out["FixedDate"] = (self.fixed.date().toString("yyyy-MM-dd")
                            if out["ReportDate"] == "Fixed" else str(self.analysis.FixedDate))
        out["EnergyEstimate"] = self.energy.isChecked()
        out.update({name: float(spin.value()) for name, spin in self.numbers.items()})
        typed = self.path.text().strip()
        out["ReportFile"] = os.path.abspath(os.path.expanduser(typed)) if typed else ""
        return out

    def problems(self) -> List[str]:
        """Why the report cannot be written with these values ([] when it can)."""
        values = self.values()
        found = report_settings.problems(SimpleNamespace(Label=self.analysis.Label, **values))
        path = values["ReportFile"]
        if not path:
            found.append("Choose the report file")
        elif os.path.splitext(path)[1].lower() not in (".pdf", ".html", ".htm"):
            found.append(f"The report file must end in .pdf or .html: {path}")
        elif not os.path.isdir(os.path.dirname(path)):
            found.append(f"The folder does not exist: {os.path.dirname(path)}")
        return found

    # -- task dialog -----------------------------------------------------------------------
    def getStandardButtons(self) -> int:  # noqa: N802 (FreeCAD API name)
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def modifyStandardButtons(self, box: Any) -> None:  # noqa: N802 (FreeCAD API name)
        ok = box.button(QtGui.QDialogButtonBox.Ok)
        if ok is not None:
            ok.setText("Write report")

    def accept(self) -> bool:
        """Save the inputs (one undo step), close, write. Wrong values keep the panel open
        with a message naming them."""
        found = self.problems()
        if found:
            QtGui.QMessageBox.warning(FreeCADGui.getMainWindow(), "Lighting report",
                                      "The report cannot be written:\n" + "\n".join(found))
            return False
        values = self.values()
        changed = report_settings.apply(self.analysis, values)
        if changed:
            FreeCAD.Console.PrintMessage(f"Lighting: report inputs saved on "
                                         f"{self.analysis.Label}: {', '.join(changed)}\n")
        self._close()
        self.written = values["ReportFile"]
        self.write(self.analysis, self.written)
        return True

    def reject(self) -> bool:
        """Close without saving or writing anything."""
        self._close()
        return True

    def _close(self) -> None:
        FreeCADGui.Control.closeDialog()
