# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of an analysis: Check / Export / Run / Cancel with a progress bar, the colour
scale, the results table (Em, Emin, Emax, U0 with CIs) and a log.

Check and the scene export run on the GUI thread (the export keeps the event loop turning);
the solver runs on a worker thread that a QTimer polls, so the GUI stays responsive and
Cancel works. Results are applied on the GUI thread in one undo step."""
from __future__ import annotations

from typing import Any, List, Optional

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from lighting.colormap import Scale
from lighting.messages import CheckError, LightingError
from lighting.objects.analysis import COLOR_MAPS, SCALE_MODES
from lighting.solver import machine, results as results_mod, store
from lighting.viewproviders import coloring
from lighting.viewproviders.base import icon_path

POLL_MS = 100
COLUMNS = ("Target", "Type", "Em lx", "Em CI", "Emin lx", "Emin CI", "Emax lx", "Emax CI",
           "U0", "U0 CI", "Check")

_last_run: Optional[machine.AnalysisRun] = None
_last_panel: Optional["AnalysisTaskPanel"] = None


def last_run() -> Optional[machine.AnalysisRun]:
    """The most recent run started from a task panel (for scripts and the GUI test)."""
    return _last_run


def last_panel() -> Optional["AnalysisTaskPanel"]:
    """The most recently opened analysis task panel."""
    return _last_panel


def _rows(result: results_mod.AnalysisResult) -> List[List[str]]:
    rows = []
    for t in result.targets:
        passed = t.passes()
        verdict = "" if passed is None else ("pass" if passed else "FAIL")
        ci = f"{t.ci_low_lux:.1f} - {t.ci_high_lux:.1f}"
        if t.kind == "grid":
            u_lo, u_hi = t.uniformity_ci
            rows.append([t.label, t.kind, f"{t.mean_lux:.1f}", ci, f"{t.min_lux:.1f}",
                         f"{t.min_ci_lux[0]:.1f} - {t.min_ci_lux[1]:.1f}", f"{t.max_lux:.1f}",
                         f"{t.max_ci_lux[0]:.1f} - {t.max_ci_lux[1]:.1f}",
                         f"{t.uniformity:.2f}", f"{u_lo:.2f} - {u_hi:.2f}", verdict])
        else:
            rows.append([t.label, t.kind, f"{t.mean_lux:.1f}", ci] + ["-"] * 6 + [verdict])
    return rows


class LegendWidget(QtGui.QWidget):
    """A horizontal colour bar with min and max labels."""

    def __init__(self, parent: Optional[QtGui.QWidget] = None) -> None:
        super().__init__(parent)
        self.scale: Optional[Scale] = None
        self.setMinimumHeight(34)

    def set_scale(self, scale: Optional[Scale]) -> None:
        self.scale = scale
        self.update()

    def paintEvent(self, event: Any) -> None:  # noqa: N802 (Qt API name)
        if self.scale is None:
            return
        painter = QtGui.QPainter(self)
        rect = self.rect().adjusted(2, 2, -2, -18)
        gradient = QtGui.QLinearGradient(rect.left(), 0, rect.right(), 0)
        for i in range(11):
            r, g, b = self.scale.colour(self.scale.min_lux + i / 10.0 *
                                        (self.scale.max_lux - self.scale.min_lux))
            gradient.setColorAt(i / 10.0, QtGui.QColor.fromRgbF(r, g, b))
        painter.fillRect(rect, QtGui.QBrush(gradient))
        painter.drawText(rect.left(), rect.bottom() + 15, f"{self.scale.min_lux:.0f} lx")
        right = f"{self.scale.max_lux:.0f} lx"
        width = painter.fontMetrics().horizontalAdvance(right) if hasattr(
            painter.fontMetrics(), "horizontalAdvance") else painter.fontMetrics().width(right)
        painter.drawText(rect.right() - width, rect.bottom() + 15, right)
        painter.end()


class AnalysisTaskPanel:
    """FreeCAD task dialog (``form`` + accept/reject) for one analysis."""

    def __init__(self, analysis: Any, autostart: bool = False) -> None:
        global _last_panel
        _last_panel = self
        self.analysis = analysis
        self.job: Optional[machine.AnalysisRun] = None
        self.form = QtGui.QWidget()
        self.form.setWindowTitle(f"Lighting analysis: {analysis.Label}")
        self.form.setWindowIcon(QtGui.QIcon(icon_path("Lighting_Analysis")))
        self._build()
        self.timer = QtCore.QTimer()
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self._poll)
        self._show_stored_results()
        if autostart:
            QtCore.QTimer.singleShot(0, self.run)

    # -- layout --------------------------------------------------------------------------
    def _build(self) -> None:
        layout = QtGui.QVBoxLayout(self.form)
        run_box = QtGui.QGroupBox("Run")
        grid = QtGui.QGridLayout(run_box)
        self.photons = QtGui.QSpinBox()
        self.photons.setRange(1, 2_000_000_000)
        self.photons.setSingleStep(100000)
        self.photons.setValue(int(self.analysis.Photons))
        self.accuracy = QtGui.QDoubleSpinBox()
        self.accuracy.setRange(0.0, 50.0)
        self.accuracy.setSuffix(" %")
        self.accuracy.setSpecialValueText("off (fixed photons)")
        self.accuracy.setValue(float(self.analysis.TargetAccuracy) * 100.0)
        grid.addWidget(QtGui.QLabel("Photons"), 0, 0)
        grid.addWidget(self.photons, 0, 1, 1, 3)
        grid.addWidget(QtGui.QLabel("Target accuracy"), 1, 0)
        grid.addWidget(self.accuracy, 1, 1, 1, 3)
        self.buttons = {}
        for column, (name, text) in enumerate((("check", "Check"), ("export", "Export scene"),
                                               ("run", "Run"), ("cancel", "Cancel"))):
            button = QtGui.QPushButton(text)
            grid.addWidget(button, 2, column)
            self.buttons[name] = button
        self.buttons["check"].clicked.connect(self.check)
        self.buttons["export"].clicked.connect(self.export)
        self.buttons["run"].clicked.connect(self.run)
        self.buttons["cancel"].clicked.connect(self.cancel)
        self.buttons["cancel"].setEnabled(False)
        self.progress = QtGui.QProgressBar()
        self.progress.setRange(0, 1000)
        self.progress.setValue(0)
        grid.addWidget(self.progress, 3, 0, 1, 4)
        self.status = QtGui.QLabel(f"Status: {self.analysis.Status}")
        self.status.setWordWrap(True)
        grid.addWidget(self.status, 4, 0, 1, 4)
        # Whether the stored results still describe the model (solver/store.results_state).
        self.state_label = QtGui.QLabel("")
        self.state_label.setWordWrap(True)
        grid.addWidget(self.state_label, 5, 0, 1, 4)
        layout.addWidget(run_box)

        display = QtGui.QGroupBox("False colours")
        form = QtGui.QGridLayout(display)
        self.colour_map = QtGui.QComboBox()
        self.colour_map.addItems(list(COLOR_MAPS))
        self.colour_map.setCurrentText(self.analysis.ColorMap)
        self.scale_mode = QtGui.QComboBox()
        self.scale_mode.addItems(list(SCALE_MODES))
        self.scale_mode.setCurrentText(self.analysis.ScaleMode)
        self.scale_min = QtGui.QDoubleSpinBox()
        self.scale_max = QtGui.QDoubleSpinBox()
        for box, value in ((self.scale_min, self.analysis.ScaleMinLux),
                           (self.scale_max, self.analysis.ScaleMaxLux)):
            box.setRange(0.0, 1.0e7)
            box.setDecimals(0)
            box.setSuffix(" lx")
            box.setValue(float(value))
        form.addWidget(QtGui.QLabel("Map"), 0, 0)
        form.addWidget(self.colour_map, 0, 1)
        form.addWidget(QtGui.QLabel("Scale"), 0, 2)
        form.addWidget(self.scale_mode, 0, 3)
        form.addWidget(QtGui.QLabel("Min"), 1, 0)
        form.addWidget(self.scale_min, 1, 1)
        form.addWidget(QtGui.QLabel("Max"), 1, 2)
        form.addWidget(self.scale_max, 1, 3)
        self.legend = LegendWidget()
        form.addWidget(self.legend, 2, 0, 1, 4)
        for widget in (self.colour_map, self.scale_mode):
            widget.currentIndexChanged.connect(self._display_changed)
        for widget in (self.scale_min, self.scale_max):
            widget.valueChanged.connect(self._display_changed)
        layout.addWidget(display)

        results_box = QtGui.QGroupBox("Results (maintained illuminance)")
        box_layout = QtGui.QVBoxLayout(results_box)
        self.table = QtGui.QTableWidget(0, len(COLUMNS))
        self.table.setHorizontalHeaderLabels(list(COLUMNS))
        self.table.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        self.table.verticalHeader().setVisible(False)
        box_layout.addWidget(self.table)
        self.facts = QtGui.QLabel("")
        box_layout.addWidget(self.facts)
        layout.addWidget(results_box)

        self.log_view = QtGui.QPlainTextEdit()
        self.log_view.setReadOnly(True)
        self.log_view.setMaximumHeight(120)
        layout.addWidget(self.log_view)

    # -- helpers -------------------------------------------------------------------------
    def log(self, level: str, text: str) -> None:
        """Show a message in the panel and the report view."""
        self.log_view.appendPlainText(f"{level}: {text}")
        line = f"Lighting: {text}\n"
        if level == "error":
            FreeCAD.Console.PrintError(line)
        elif level == "warning":
            FreeCAD.Console.PrintWarning(line)
        else:
            FreeCAD.Console.PrintMessage(line)

    def _set_status(self, text: str) -> None:
        self.status.setText(f"Status: {text}")

    def _busy(self, running: bool) -> None:
        for name in ("check", "export", "run"):
            self.buttons[name].setEnabled(not running)
        self.buttons["cancel"].setEnabled(running)

    def _write_settings(self) -> None:
        # One "Lighting settings" undo step only when a value really changes.
        store.write_settings(self.analysis, Photons=self.photons.value(),
                             TargetAccuracy=self.accuracy.value() / 100.0)

    def show_state(self, state: Optional[Any] = None) -> None:
        """Show whether the stored results are current or stale (red, with what changed)."""
        try:
            state = state or store.results_state(self.analysis)
            stale = state.state in ("stale", "unknown")
            self.state_label.setText(state.text())
            self.state_label.setStyleSheet("color: #c62828; font-weight: bold;" if stale else "")
        except Exception:  # noqa: BLE001 - the panel was closed or the analysis deleted
            pass

    def _display_changed(self, *args: Any) -> None:
        a = self.analysis
        a.ColorMap = self.colour_map.currentText()
        a.ScaleMode = self.scale_mode.currentText()
        a.ScaleMinLux = self.scale_min.value()
        a.ScaleMaxLux = self.scale_max.value()
        fixed = a.ScaleMode == "Fixed"
        self.scale_min.setEnabled(fixed)
        self.scale_max.setEnabled(fixed)
        self.legend.set_scale(coloring.scale_for(a))
        coloring.refresh(a)

    def _show_stored_results(self) -> None:
        result = store.load_from_document(self.analysis)
        fixed = self.analysis.ScaleMode == "Fixed"
        self.scale_min.setEnabled(fixed)
        self.scale_max.setEnabled(fixed)
        self.legend.set_scale(coloring.scale_for(self.analysis) if result else None)
        self.table.setRowCount(0)
        self.show_state()
        if result is None:
            self.facts.setText("No results yet: press Run.")
            return
        for row, values in enumerate(_rows(result)):
            self.table.insertRow(row)
            for column, value in enumerate(values):
                item = QtGui.QTableWidgetItem(value)
                if value == "FAIL":
                    item.setForeground(QtGui.QBrush(QtGui.QColor(200, 0, 0)))
                self.table.setItem(row, column, item)
        self.table.resizeColumnsToContents()
        facts = (f"{result.photons:.0f} photons, {result.seconds:.2f} s, "
                 f"{result.confidence * 100:g} % confidence intervals")
        if result.partial:
            facts += " - PARTIAL (cancelled)"
        self.facts.setText(facts)

    def _pump(self, text: str) -> None:
        self._set_status(text)
        QtGui.QApplication.processEvents(QtCore.QEventLoop.ExcludeUserInputEvents)

    # -- actions -------------------------------------------------------------------------
    def check(self) -> bool:
        """Run the Check stage and report."""
        self._write_settings()
        job = machine.AnalysisRun(self.analysis, log=self.log)
        try:
            report = job.check()
        except CheckError as exc:
            self._set_status("check failed (see the log)")
            self.log("error", str(exc).splitlines()[0])
            return False
        self._set_status(f"check passed ({len(report.warnings)} warning(s))")
        return True

    def export(self) -> Optional[str]:
        """Check without the solver and write the scene file."""
        self._write_settings()
        job = machine.AnalysisRun(self.analysis, log=self.log)
        try:
            job.check(need_solver=False)
            path = job.prepare(progress=self._pump)
        except LightingError as exc:
            self._set_status("export failed (see the log)")
            self.log("error", str(exc).splitlines()[0])
            return None
        self._set_status(f"scene written: {path}")
        return path

    def run(self) -> None:
        """Check and Prepare now, then Solve on a worker thread."""
        global _last_run
        if self.job is not None and not self.job.finished:
            return
        self._write_settings()
        # One core stays free for the GUI; results do not depend on the thread count.
        self.job = machine.AnalysisRun(self.analysis, log=self.log, spare_core=True)
        _last_run = self.job
        self._busy(True)
        self.progress.setValue(0)
        try:
            self.job.check()
            self.job.prepare(progress=self._pump)
            self.job.start()
        except LightingError as exc:
            message = self.job.fail(exc)
            self._busy(False)
            self._set_status(f"{self.job.stage}: {message.splitlines()[0]}")
            self.log("error", message)
            return
        except Exception as exc:  # noqa: BLE001 - never leave the panel stuck
            message = self.job.fail(exc)
            self._busy(False)
            self._set_status(f"failed: {message}")
            self.log("error", message)
            return
        self._set_status("solving...")
        self.timer.start()

    def cancel(self) -> None:
        """Ask the solver to stop; partial results are kept."""
        if self.job is not None and not self.job.finished:
            self.job.cancel()
            self._set_status("cancelling...")

    def _poll(self) -> None:
        job = self.job
        if job is None:
            self.timer.stop()
            return
        if job.total > 0:
            self.progress.setValue(int(1000.0 * min(job.done / job.total, 1.0)))
        if not job.finished:
            self._set_status(f"solving: {job.done:,} / {job.total:,} photons")
            return
        self.timer.stop()
        self._busy(False)
        if job.error is not None:
            message = job.fail(job.error)
            self._set_status(f"{job.stage}: {message.splitlines()[0]}")
            self.log("error" if job.stage == "failed" else "warning", message)
            return
        try:
            result = job.apply()
        except Exception as exc:  # noqa: BLE001 - e.g. the document was closed
            message = job.fail(exc)
            self._set_status(f"failed: {message}")
            self.log("error", message)
            return
        self.progress.setValue(1000)
        self._set_status(self.analysis.Status)
        self.log("info", "Results:\n" + result.table())
        self.log("info", store.summary_line(result))  # last: the status bar shows this line
        self._show_stored_results()
        FreeCADGui.updateGui()

    # -- task dialog protocol -------------------------------------------------------------
    def getStandardButtons(self) -> int:  # noqa: N802 (FreeCAD API name)
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self) -> bool:
        """Close: cancel a running solve first (waits briefly for the worker)."""
        if self.job is not None and not self.job.finished:
            self.job.cancel()
            self.job.wait(5.0)
        self.timer.stop()
        FreeCADGui.Control.closeDialog()
        try:
            FreeCADGui.ActiveDocument.resetEdit()
        except Exception:  # noqa: BLE001 - not in edit mode
            pass
        return True

    def accept(self) -> bool:
        return self.reject()
