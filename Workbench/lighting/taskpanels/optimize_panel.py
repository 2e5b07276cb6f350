# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel "Optimize placement": the intention (target, goal, required levels), the search
budget, Run / Cancel / Apply, live progress with an estimated time left, and the set of
statistically indistinguishable optima.

Laid out for the default combo view (about 264 px wide): every label sits above its field, the
buttons come before the result list, and the list's details are in tooltips. The scene export
runs on the GUI thread (it reads the document); the search runs on a worker thread that a
QTimer polls (the module releases the GIL and reports after every trace), so the GUI stays
responsive and Cancel stops within one trace. Apply leaves exactly the chosen layout's
luminaires for the domains, in one undo step; luminaires the domains do not own are touched
only if the user said so when the search started."""
from __future__ import annotations

import threading
import time
from typing import Any, Dict, List, Optional

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from lighting.export.scene import default_output_directory
from lighting.messages import LightingError
from lighting.objects import analysis as analysis_mod
from lighting.solver import optimize, run
from lighting.viewproviders.base import icon_path
from lighting.taskpanels.modeless import ModelessPanel
from lighting.taskpanels.optimize_decide import OptimizeDecide

POLL_MS = 100
CONSOLE_EVERY_S = 5.0  # progress lines in the report view, not one per trace
DEFAULT_EVALUATIONS = 200
GOAL_TEXT = {"minimize_installed_flux": "Meet Em and U0 with the least flux",
             "maximize_uniformity": "Best uniformity U0 at the required Em",
             "maximize_mean_illuminance": "Most light (maximise Em)",
             "minimize_mean_illuminance": "Least light (minimise Em)"}

_last_panel: Optional["OptimizeTaskPanel"] = None


def last_panel() -> Optional["OptimizeTaskPanel"]:
    """The most recently opened panel (for scripts and the GUI test)."""
    return _last_panel


def traced_share(counters: Dict[str, Any]) -> str:
    """", N % of their photons traced" where reused luminaire traces saved some, else ""."""
    asked, traced = counters.get("photons", 0), counters.get("photons_traced", 0)
    if not asked or traced >= asked:
        return ""
    return f", {100.0 * traced / asked:.0f} % of their photons traced"


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
        self.started = time.monotonic()
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


def _field(layout: QtGui.QVBoxLayout, label: str, widget: QtGui.QWidget) -> QtGui.QWidget:
    """A label above its field: the combo view is too narrow for side-by-side rows."""
    layout.addWidget(_label(label))
    widget.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Fixed)
    layout.addWidget(widget)
    return widget


def _label(text: str) -> QtGui.QLabel:
    """A label that wraps instead of widening the panel."""
    label = QtGui.QLabel(text)
    label.setWordWrap(True)
    label.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Preferred)
    return label


def _spin(low: int, high: int, value: int, special: str = "") -> QtGui.QSpinBox:
    spin = QtGui.QSpinBox()
    spin.setRange(low, high)
    if special:
        spin.setSpecialValueText(special)
    spin.setValue(value)
    return spin


class OptimizeTaskPanel(ModelessPanel):
    """FreeCAD task dialog (``form`` + accept/reject) for one analysis' placement domains."""

    def __init__(self, analysis: Any) -> None:
        global _last_panel
        _last_panel = self
        self.analysis = analysis
        self.job: Optional[SearchJob] = None
        self.result: Optional[optimize.PlacementResult] = None
        self.targets = analysis_mod.targets(analysis)
        self._console_at = 0.0
        self.form = QtGui.QWidget()
        # Short: the task box's title bar does not wrap and would widen the panel.
        self.form.setWindowTitle("Optimize placement")
        self.form.setToolTip(f"Placement domains of {analysis.Label}")
        self.form.setWindowIcon(QtGui.QIcon(icon_path("Lighting_Optimize")))
        self._build()
        self.timer = QtCore.QTimer()
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self._poll)
        self._target_changed()

    # -- layout -------------------------------------------------------------------------
    def _build(self) -> None:
        layout = QtGui.QVBoxLayout(self.form)
        layout.addWidget(self._intention_box())
        layout.addWidget(self._budget_box())
        row = QtGui.QGridLayout()  # two by two: Run Cancel / Apply Decide
        self.buttons = {}
        for name, text, tip in (("run", "Run", "Export the model and search"),
                                ("cancel", "Cancel", "Stop; the optima found so far are kept"),
                                ("apply", "Apply", "Leave exactly the selected layout's "
                                                   "luminaires (one undo step)")):
            button = QtGui.QPushButton(text)
            button.setToolTip(tip)
            button.setMinimumWidth(40)
            button.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Fixed)
            row.addWidget(button, len(self.buttons) // 2, len(self.buttons) % 2)
            self.buttons[name] = button
        # Decide for the chosen layout (taskpanels/optimize_decide.py).
        self.decider = OptimizeDecide(self)
        self.buttons["decide"] = self.decider.button
        row.addWidget(self.decider.button, 1, 1)
        self.buttons["run"].clicked.connect(self.run)
        self.buttons["cancel"].clicked.connect(self.cancel)
        self.buttons["apply"].clicked.connect(self.apply)
        self.buttons["cancel"].setEnabled(False)
        self.buttons["apply"].setEnabled(False)
        layout.addLayout(row)
        self.progress = QtGui.QProgressBar()
        self.progress.setRange(0, 1)
        self.progress.setValue(0)
        self.progress.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Fixed)
        layout.addWidget(self.progress)
        self.status = QtGui.QLabel("Each placement domain places its Template luminaire "
                                   "(up to MaxLuminaires of them) on its candidates.")
        self.status.setWordWrap(True)
        self.status.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Preferred)
        layout.addWidget(self.status)
        layout.addWidget(self.decider.label)
        layout.addWidget(_label("Optima, best first (details: tooltip)"))
        self.table = QtGui.QTableWidget(0, 2)
        self.table.setHorizontalHeaderLabels(["Layout", "Em / U0"])
        self.table.setSelectionBehavior(QtGui.QAbstractItemView.SelectRows)
        self.table.setSelectionMode(QtGui.QAbstractItemView.SingleSelection)
        self.table.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        self.table.horizontalHeader().setStretchLastSection(True)
        self.table.verticalHeader().setVisible(False)
        self.table.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Expanding)
        layout.addWidget(self.table)

    def _intention_box(self) -> QtGui.QGroupBox:
        box = QtGui.QGroupBox("Intention")
        col = QtGui.QVBoxLayout(box)
        self.target = _field(col, "Target", QtGui.QComboBox())
        self.target.addItems([t.Label for t in self.targets])
        self.target.currentIndexChanged.connect(self._target_changed)
        self.goal = _field(col, "Goal", QtGui.QComboBox())
        for key, text in GOAL_TEXT.items():
            self.goal.addItem(text, key)
        self.goal.currentIndexChanged.connect(self._goal_changed)
        self.min_lux = _field(col, "Required Em", QtGui.QDoubleSpinBox())
        self.min_lux.setRange(0.0, 1.0e6)
        self.min_lux.setSuffix(" lx")
        self.min_lux.setValue(500.0)
        self.min_u0 = _field(col, "Required U0", QtGui.QDoubleSpinBox())
        self.min_u0.setRange(0.0, 1.0)
        self.min_u0.setSingleStep(0.05)
        self.min_u0.setValue(0.6)
        return box

    def _budget_box(self) -> QtGui.QGroupBox:
        box = QtGui.QGroupBox("Search budget")
        col = QtGui.QVBoxLayout(box)
        self.evaluations = _field(col, "Evaluations (traces: the time)",
                                  _spin(0, 10_000_000, DEFAULT_EVALUATIONS, "no limit"))
        self.iterations = _field(col, "Iterations", _spin(1, 1_000_000, 200))
        # The adaptive photon counts (paper Sec. IV-A): n screens every candidate, N confirms
        # the promising ones. 0 = the optimizer's defaults.
        self.screening = _field(col, "Screening photons n", _spin(0, 2_000_000_000, 0, "default"))
        self.confirmation = _field(col, "Confirmation photons N",
                                   _spin(0, 2_000_000_000, 0, "default"))
        for spin in (self.screening, self.confirmation):
            spin.setSingleStep(10000)
        return box

    # -- intention ------------------------------------------------------------------------
    def _target_changed(self, *args: Any) -> None:
        """What the target asks for becomes the default intention (docs/optimization.md §12)."""
        if not self.targets:
            return
        target = self.targets[self.target.currentIndex()]
        goal, lux, u0 = optimize.default_intention(target)
        self.goal.setCurrentIndex(self.goal.findData(goal))
        if lux is not None:
            self.min_lux.setValue(lux)
        if u0 is not None:
            self.min_u0.setValue(u0)
        self._goal_changed()

    def refresh(self) -> None:
        """The document changed (taskpanels/sync.py): the target list follows the analysis'
        targets (one added, deleted, renamed, an Undo); the chosen target stays chosen."""
        targets = analysis_mod.targets(self.analysis)
        try:
            shown = [(t.Name, t.Label) for t in self.targets]
            chosen = self.targets[self.target.currentIndex()].Name if self.targets and \
                self.target.currentIndex() >= 0 else None
        except Exception:  # noqa: BLE001 - a shown target was deleted
            shown, chosen = [], None
        if [(t.Name, t.Label) for t in targets] == shown:
            return
        self.targets = targets
        names = [t.Name for t in targets]
        self.target.blockSignals(True)  # the user's intention stays unless the target changes
        self.target.clear()
        self.target.addItems([t.Label for t in targets])
        self.target.setCurrentIndex(names.index(chosen) if chosen in names else 0)
        self.target.blockSignals(False)
        if chosen not in names:
            self._target_changed()

    def is_busy(self) -> bool:
        """True while a search or a Decide run of this panel is running."""
        searching = self.job is not None and not self.job.finished
        return searching or self.decider.is_busy()

    def selected_member(self) -> int:
        """The layout chosen in the list (0: the best)."""
        rows = self.table.selectionModel().selectedRows()
        return rows[0].row() if rows else 0

    def set_busy(self, running: bool) -> None:
        """Buttons while a search or a Decide run is in progress."""
        self._busy(running)

    def _goal_changed(self, *args: Any) -> None:
        goal = self.goal.currentData()
        self.min_lux.setEnabled(goal in ("maximize_uniformity", "minimize_installed_flux"))
        self.min_u0.setEnabled(goal == "minimize_installed_flux")

    def _busy(self, running: bool) -> None:
        self.buttons["run"].setEnabled(not running)
        self.buttons["cancel"].setEnabled(running)
        chosen = not running and self.result is not None and bool(self.result.members)
        self.buttons["apply"].setEnabled(chosen)
        self.decider.enable(chosen)

    def ask_replace_others(self, others: List[Any]) -> Optional[bool]:
        """Ask before the search whether the other luminaires on the domains' faces are to
        be replaced (True), kept (False); None: the user cancelled."""
        names = ", ".join(o.Label for o in others)
        box = QtGui.QMessageBox(
            QtGui.QMessageBox.Question, "Optimize placement",
            f"{names} {'is' if len(others) == 1 else 'are'} on a placement domain's face but "
            "not placed by it.\n\nReplace them with the optimized layout? They are left out "
            "of the search and deleted when you apply a result.\n\nNo: they stay where they "
            "are, untouched, and their light counts.",
            QtGui.QMessageBox.Yes | QtGui.QMessageBox.No | QtGui.QMessageBox.Cancel,
            FreeCADGui.getMainWindow())
        box.setObjectName("LightingOptimizeReplaceOthers")
        answer = box.exec_()
        if answer == QtGui.QMessageBox.Cancel:
            return None
        return answer == QtGui.QMessageBox.Yes

    # -- run --------------------------------------------------------------------------------
    def run(self) -> None:
        """Export on the GUI thread, then search on a worker thread."""
        if self.job is not None and not self.job.finished:
            return
        if not self.targets:
            self.status.setText("The analysis has no target to optimize for.")
            return
        others = optimize.others_on_domains(self.analysis)
        replace = self.ask_replace_others(others) if others else False
        if replace is None:
            return
        goal = self.goal.currentData()
        try:
            prepared = optimize.prepare(
                self.analysis, self.targets[self.target.currentIndex()], goal,
                self.min_lux.value() if self.min_lux.isEnabled() else None,
                self.min_u0.value() if self.min_u0.isEnabled() else None,
                self.iterations.value(), int(self.analysis.Seed),
                default_output_directory(self.analysis), self.evaluations.value() or None,
                replace_others=replace)
        except (LightingError, ValueError) as exc:
            report = getattr(exc, "report", None)
            self.status.setText(report.format() if report is not None else str(exc))
            return
        self.result = None
        self.decider.forget()
        self.table.setRowCount(0)
        self.job = SearchJob(prepared, self.screening.value() or None,
                             self.confirmation.value() or None)
        self.job.thread.start()
        budget = self.evaluations.value()
        self.progress.setRange(0, budget if budget else 0)  # 0, 0: busy indicator
        self.progress.setValue(0)
        self._busy(True)
        self.status.setText("searching: first trace...")
        self._console_at = 0.0
        FreeCAD.Console.PrintMessage(f"Optimize placement: searching ({GOAL_TEXT[goal]})\n")
        self.timer.start()

    def cancel(self) -> None:
        """Stop the search (the optima found so far are kept) or the Decide run."""
        self.decider.cancel()
        if self.job is not None and not self.job.finished and self.job.cancel_token is not None:
            self.job.cancel_token.cancel()
            self.status.setText("cancelling...")

    def progress_text(self) -> str:
        """The progress line shown now (empty before the first trace)."""
        if self.job is None or not self.job.latest:
            return ""
        prepared = self.job.prepared
        return optimize.format_progress(self.job.latest, prepared.max_iterations,
                                        prepared.max_evaluations)

    def _poll(self) -> None:
        job = self.job
        if job is None:
            self.timer.stop()
            return
        if not job.finished:
            text = self.progress_text()
            if text:
                if self.progress.maximum() > 0:
                    self.progress.setValue(min(self.progress.maximum(),
                                               int(job.latest.get("evaluations", 0))))
                if not self.status.text().startswith("cancelling"):
                    self.status.setText(text)
                now = time.monotonic()
                if now - self._console_at >= CONSOLE_EVERY_S:
                    self._console_at = now
                    FreeCAD.Console.PrintMessage(f"Optimize placement: {text}\n")
            return
        self.timer.stop()
        if job.error is not None:
            self.result = None
            self._busy(False)
            self.status.setText(f"failed: {job.error}")
            FreeCAD.Console.PrintError(f"Optimize placement failed: {job.error}\n")
            return
        self.result = job.result
        self.progress.setRange(0, 1)
        self.progress.setValue(1)
        self._busy(False)
        self._fill_table()

    def _fill_table(self) -> None:
        members = self.result.members if self.result is not None else []
        self.table.setRowCount(len(members))
        flux = self.goal.currentData() == "minimize_installed_flux"
        for row, m in enumerate(members):
            lo, hi = m["ci"]
            objective = f"{m['mean']:.0f} lm" if flux else f"{m['mean']:.4g}"
            levels = m["constraints"]
            em_u0 = " / ".join(f"{v:.3g}" for v in levels) if levels else "-"
            where = "\n".join(f"{name}: ({x:.2f}, {y:.2f}, {z:.2f}) m"
                              for name, (x, y, z) in m["positions_m"].items())
            tip = f"objective {m['mean']:.4g} (CI {lo:.4g} - {hi:.4g})\n{where}"
            for column, text in enumerate((f"{m['count']} lum., {objective}", em_u0)):
                item = QtGui.QTableWidgetItem(text)
                item.setToolTip(tip)
                self.table.setItem(row, column, item)
        self.table.resizeColumnToContents(0)
        if members:
            self.table.selectRow(0)
        raw = self.result.raw if self.result is not None else {}
        counters = raw.get("counters", {})
        text = (f"{len(members)} layout(s) statistically indistinguishable from the best "
                f"({raw.get('stop', '')}, {counters.get('evaluations', 0)} evaluations"
                f"{traced_share(counters)})")
        text += "; select one and Apply." if members else \
            ": none meets the requirements - raise MaxLuminaires or the budget."
        self.status.setText(text)
        FreeCAD.Console.PrintMessage(f"Optimize placement: {text}\n")

    def apply(self) -> List[Any]:
        """Leave exactly the selected layout's luminaires (one undo step)."""
        if self.result is None or not self.result.members:
            return []
        member = self.selected_member()
        removed = [o.Label for o in self.result.removed]
        placed = self.result.apply(member)
        self.decider.was_applied(member)
        text = f"applied layout {member + 1}: {len(placed)} luminaire(s) placed"
        if removed:
            text += f", removed {', '.join(removed)}"
        self.status.setText(text)
        FreeCAD.Console.PrintMessage(f"Optimize placement: {text}\n")
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
        if self.decider.job is not None:
            self.decider.job.wait(5.0)
        self.timer.stop()
        self.decider.timer.stop()
        FreeCADGui.Control.closeDialog()
        return True

    def accept(self) -> bool:
        return self.reject()
