# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel "Optimize placement": the intention (target, goal, required levels), Run / Cancel
with live progress, the set of statistically indistinguishable optima, and Apply.

The scene export runs on the GUI thread (it reads the document); the search runs on a worker
thread that a QTimer polls (the module releases the GIL), so the GUI stays responsive and
Cancel stops within one trace. Apply moves the luminaires in one undo step."""
from __future__ import annotations

import threading
from typing import Any, Dict, List, Optional

import FreeCADGui
from PySide import QtCore, QtGui

from lighting.export.scene import default_output_directory
from lighting.messages import LightingError
from lighting.objects import analysis as analysis_mod
from lighting.solver import optimize, run
from lighting.viewproviders.base import icon_path

POLL_MS = 100
GOAL_TEXT = {"maximize_uniformity": "Maximise uniformity U0 (at a required Em)",
             "minimize_installed_flux": "Minimise installed flux (at required Em and U0)",
             "maximize_mean_illuminance": "Maximise mean illuminance",
             "minimize_mean_illuminance": "Minimise mean illuminance"}

_last_panel: Optional["OptimizeTaskPanel"] = None


def last_panel() -> Optional["OptimizeTaskPanel"]:
    """The most recently opened panel (for scripts and the GUI test)."""
    return _last_panel


class SearchJob:
    """The worker thread's state, read by the GUI thread's timer."""

    def __init__(self, prepared: optimize.PreparedSearch, screening: Optional[int],
                 confirmation: Optional[int]) -> None:
        self.prepared = prepared
        self.photons = (screening, confirmation)
        self.cancel_token = run.make_cancel_token()
        self.latest: Dict[str, Any] = {}
        self.result: Optional[optimize.PlacementResult] = None
        self.error: Optional[BaseException] = None
        self.thread = threading.Thread(target=self._work, name="lighting-optimize", daemon=True)

    def _progress(self, stats: Dict[str, Any]) -> bool:
        self.latest = dict(stats)
        return True

    def _work(self) -> None:
        try:
            self.result = optimize.search(self.prepared, self._progress, *self.photons,
                                          cancel=self.cancel_token)
        except BaseException as exc:  # noqa: BLE001 - reported on the GUI thread
            self.error = exc

    @property
    def finished(self) -> bool:
        return not self.thread.is_alive()


class OptimizeTaskPanel:
    """FreeCAD task dialog (``form`` + accept/reject) for one analysis' placement domains."""

    def __init__(self, analysis: Any) -> None:
        global _last_panel
        _last_panel = self
        self.analysis = analysis
        self.job: Optional[SearchJob] = None
        self.result: Optional[optimize.PlacementResult] = None
        self.targets = analysis_mod.targets(analysis)
        self.form = QtGui.QWidget()
        self.form.setWindowTitle(f"Optimize placement: {analysis.Label}")
        self.form.setWindowIcon(QtGui.QIcon(icon_path("Lighting_Optimize")))
        self._build()
        self.timer = QtCore.QTimer()
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self._poll)
        self._goal_changed()

    def _build(self) -> None:
        layout = QtGui.QVBoxLayout(self.form)
        box = QtGui.QGroupBox("Intention")
        grid = QtGui.QGridLayout(box)
        self.target = QtGui.QComboBox()
        self.target.addItems([t.Label for t in self.targets])
        self.goal = QtGui.QComboBox()
        for key, text in GOAL_TEXT.items():
            self.goal.addItem(text, key)
        self.goal.currentIndexChanged.connect(self._goal_changed)
        self.min_lux = QtGui.QDoubleSpinBox()
        self.min_lux.setRange(0.0, 1.0e6)
        self.min_lux.setSuffix(" lx")
        self.min_lux.setValue(500.0)
        self.min_u0 = QtGui.QDoubleSpinBox()
        self.min_u0.setRange(0.0, 1.0)
        self.min_u0.setSingleStep(0.05)
        self.min_u0.setValue(0.6)
        self.iterations = QtGui.QSpinBox()
        self.iterations.setRange(1, 1_000_000)
        self.iterations.setValue(200)
        # The adaptive photon counts (paper Sec. IV-A): n screens every candidate, N confirms
        # the promising ones. 0 = the optimizer's defaults.
        self.screening, self.confirmation = QtGui.QSpinBox(), QtGui.QSpinBox()
        for spin in (self.screening, self.confirmation):
            spin.setRange(0, 2_000_000_000)
            spin.setSingleStep(10000)
            spin.setSpecialValueText("default")
            spin.setValue(0)
        rows = (("Target", self.target), ("Goal", self.goal), ("Required Em", self.min_lux),
                ("Required U0", self.min_u0), ("Iterations", self.iterations),
                ("Screening photons n", self.screening),
                ("Confirmation photons N", self.confirmation))
        for row, (label, widget) in enumerate(rows):
            grid.addWidget(QtGui.QLabel(label), row, 0)
            grid.addWidget(widget, row, 1, 1, 3)
        self.buttons = {}
        for column, (name, text) in enumerate((("run", "Run"), ("cancel", "Cancel"),
                                               ("apply", "Apply selected"))):
            self.buttons[name] = QtGui.QPushButton(text)
            grid.addWidget(self.buttons[name], len(rows), column)
        self.buttons["run"].clicked.connect(self.run)
        self.buttons["cancel"].clicked.connect(self.cancel)
        self.buttons["apply"].clicked.connect(self.apply)
        self.buttons["cancel"].setEnabled(False)
        self.buttons["apply"].setEnabled(False)
        self.status = QtGui.QLabel("Each placement domain places its Template luminaire "
                                   "(MaxLuminaires of them) on its candidates.")
        self.status.setWordWrap(True)
        grid.addWidget(self.status, len(rows) + 1, 0, 1, 4)
        layout.addWidget(box)
        self.table = QtGui.QTableWidget(0, 3)
        self.table.setHorizontalHeaderLabels(["Objective", "CI", "Positions (m)"])
        self.table.setSelectionBehavior(QtGui.QAbstractItemView.SelectRows)
        self.table.setSelectionMode(QtGui.QAbstractItemView.SingleSelection)
        self.table.horizontalHeader().setStretchLastSection(True)
        layout.addWidget(QtGui.QLabel("Statistically indistinguishable optima, best first"))
        layout.addWidget(self.table)

    def _goal_changed(self, *args: Any) -> None:
        goal = self.goal.currentData()
        self.min_lux.setEnabled(goal in ("maximize_uniformity", "minimize_installed_flux"))
        self.min_u0.setEnabled(goal == "minimize_installed_flux")

    def _busy(self, running: bool) -> None:
        self.buttons["run"].setEnabled(not running)
        self.buttons["cancel"].setEnabled(running)
        self.buttons["apply"].setEnabled(not running and self.result is not None)

    def run(self) -> None:
        """Export on the GUI thread, then search on a worker thread."""
        if self.job is not None and not self.job.finished:
            return
        if not self.targets:
            self.status.setText("The analysis has no target to optimize for.")
            return
        goal = self.goal.currentData()
        try:
            prepared = optimize.prepare(
                self.analysis, self.targets[self.target.currentIndex()], goal,
                self.min_lux.value() if self.min_lux.isEnabled() else None,
                self.min_u0.value() if self.min_u0.isEnabled() else None,
                self.iterations.value(), int(self.analysis.Seed),
                default_output_directory(self.analysis))
        except (LightingError, ValueError) as exc:
            report = getattr(exc, "report", None)
            self.status.setText(report.format() if report is not None else str(exc))
            return
        self.result = None
        self.job = SearchJob(prepared, self.screening.value() or None,
                             self.confirmation.value() or None)
        self.job.thread.start()
        self._busy(True)
        self.status.setText("searching...")
        self.timer.start()

    def cancel(self) -> None:
        """Stop the search; the optima found so far are kept."""
        if self.job is not None and not self.job.finished and self.job.cancel_token is not None:
            self.job.cancel_token.cancel()
            self.status.setText("cancelling...")

    def _poll(self) -> None:
        job = self.job
        if job is None:
            self.timer.stop()
            return
        if not job.finished:
            s = job.latest
            if s:
                self.status.setText(f"iteration {s.get('iteration', 0)} of "
                                    f"{self.iterations.value()}: {s.get('isoc_size', 0)} "
                                    f"optimum/optima, {s.get('total_photons', 0):,} photons")
            return
        self.timer.stop()
        if job.error is not None:
            self.result = None
            self._busy(False)
            self.status.setText(f"failed: {job.error}")
            return
        self.result = job.result
        self._busy(False)
        self._fill_table()

    def _fill_table(self) -> None:
        members = self.result.members if self.result is not None else []
        self.table.setRowCount(len(members))
        for row, m in enumerate(members):
            lo, hi = m["ci"]
            where = "; ".join(f"{name}: ({x:.2f}, {y:.2f}, {z:.2f})"
                              for name, (x, y, z) in m["positions_m"].items())
            for column, text in enumerate((f"{m['mean']:.4g}", f"{lo:.4g} - {hi:.4g}", where)):
                self.table.setItem(row, column, QtGui.QTableWidgetItem(text))
        if members:
            self.table.selectRow(0)
        stop = self.result.raw.get("stop", "") if self.result is not None else ""
        self.status.setText(f"{len(members)} statistically indistinguishable optimum/optima "
                            f"({stop}); select one and Apply.")

    def apply(self) -> List[Any]:
        """Move the luminaires to the selected optimum (one undo step)."""
        if self.result is None or not self.result.members:
            return []
        rows = self.table.selectionModel().selectedRows()
        member = rows[0].row() if rows else 0
        doc = self.analysis.Document
        doc.openTransaction("Apply optimized placement")
        try:
            placed = self.result.apply(member)
        finally:
            doc.commitTransaction()
        self.status.setText(f"applied optimum {member + 1}: moved "
                            f"{', '.join(o.Label for o in placed)}")
        FreeCADGui.updateGui()
        return placed

    # -- task dialog protocol -------------------------------------------------------------
    def getStandardButtons(self) -> int:  # noqa: N802 (FreeCAD API name)
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self) -> bool:
        """Close: stop a running search first."""
        self.cancel()
        if self.job is not None:
            self.job.thread.join(5.0)
        self.timer.stop()
        FreeCADGui.Control.closeDialog()
        return True

    def accept(self) -> bool:
        return self.reject()
