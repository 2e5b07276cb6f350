# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of an analysis: Check / Export / Run / Cancel with a progress bar, the results
table (taskpanels/results_table.py), what deciding the undecided requirements costs with a
one-click Decide (decide_view.py), the light scenes, the colour scale (display_view.py), the
plan view, accuracy vs time and a log. It fits FreeCAD's default
combo view (about 264 px): a fixed header with the buttons, sections that scroll below it
(``add_section``); it is modeless, so the toolbars stay usable while it is open.

Check and the scene export run on the GUI thread (the export keeps the event loop turning);
the solver runs on a worker thread that a QTimer polls, so the GUI stays responsive and
Cancel works. Results are applied on the GUI thread in one undo step."""
from __future__ import annotations

from typing import Any, Dict, Optional

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from lighting.messages import CheckError, LightingError
from lighting.solver import machine, store
from lighting.taskpanels import light_scene_view, plan_view, study_view
from lighting.taskpanels.decide_view import DecideView
from lighting.taskpanels.display_view import DisplayView, stacked_form
from lighting.taskpanels.modeless import ModelessPanel
from lighting.taskpanels.results_table import COLUMNS, ESSENTIAL_COLUMNS  # noqa: F401 (API)
from lighting.taskpanels.results_table import VERDICT_COLOURS  # noqa: F401 (API)
from lighting.taskpanels.results_table import ResultsTable, facts_text, rows, seconds_text
from lighting.viewproviders.base import icon_path

POLL_MS = 100

_last_run: Optional[machine.AnalysisRun] = None
_last_panel: Optional["AnalysisTaskPanel"] = None


def last_run() -> Optional[machine.AnalysisRun]:
    """The most recent run started from a task panel (for scripts and the GUI test)."""
    return _last_run


def last_panel() -> Optional["AnalysisTaskPanel"]:
    """The most recently opened analysis task panel."""
    return _last_panel


def panel_of(analysis: Any) -> Optional["AnalysisTaskPanel"]:
    """The open analysis panel when it shows ``analysis``, else None (also when the panel's
    own analysis has been deleted)."""
    panel = _last_panel
    try:
        if panel is not None and (panel.analysis.Document.Name, panel.analysis.Name) == \
                (analysis.Document.Name, analysis.Name):
            return panel
    except Exception:  # noqa: BLE001 - the panel's analysis was deleted
        pass
    return None


#: The table's rows of a result (taskpanels/results_table.py; kept for scripts).
_rows = rows


class AnalysisTaskPanel(ModelessPanel):
    """FreeCAD task dialog (``form`` + accept/reject) for one analysis."""

    def __init__(self, analysis: Any, autostart: bool = False) -> None:
        global _last_panel
        _last_panel = self
        self.analysis = analysis
        self.job: Optional[machine.AnalysisRun] = None
        self.form = QtGui.QWidget()
        # The task box does not elide its title, and the title's width is the panel's least
        # width: the analysis' label only, cut short.
        label = analysis.Label if len(analysis.Label) <= 24 else analysis.Label[:23] + "\u2026"
        self.form.setWindowTitle(label)
        self.form.setWindowIcon(QtGui.QIcon(icon_path("Lighting_Analysis")))
        self._build()
        self.timer = QtCore.QTimer()
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self._poll)
        self._seen = self._document_settings()  # what _show_settings compares against
        self.refresh()
        if autostart:
            QtCore.QTimer.singleShot(0, self.run)

    # -- layout --------------------------------------------------------------------------
    # The combo view is about 264 px wide at FreeCAD's default window size: every section
    # stacks its rows vertically (labels above their fields where needed), the action
    # buttons sit in a header that never scrolls, and the sections below scroll vertically.
    def _build(self) -> None:
        #: Sections of the scrolling body by name, in order (add_section adds more).
        self.sections: Dict[str, QtGui.QGroupBox] = {}
        outer = QtGui.QVBoxLayout(self.form)
        outer.setContentsMargins(0, 0, 0, 0)
        self.header = self._build_header()
        outer.addWidget(self.header)
        self.scroll = QtGui.QScrollArea()
        self.scroll.setWidgetResizable(True)
        self.scroll.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        self.scroll.setFrameShape(QtGui.QFrame.NoFrame)
        body = QtGui.QWidget()
        self.body_layout = QtGui.QVBoxLayout(body)
        self.body_layout.setContentsMargins(0, 0, 0, 0)
        self.body_layout.addStretch(1)
        self.scroll.setWidget(body)
        outer.addWidget(self.scroll, 1)
        self.add_section("settings", "Run settings", self._build_settings())
        self.add_section("results", "Results", self._build_results())
        self.decide_view = DecideView(self.decide_now)
        undecided = QtGui.QVBoxLayout()
        undecided.addWidget(self.decide_view)
        self.add_section("undecided", "Undecided: what deciding costs", undecided)
        self.scene_view = light_scene_view.LightSceneView(self.analysis,
                                                          self._show_stored_results)
        scenes = QtGui.QVBoxLayout()
        scenes.addWidget(self.scene_view)
        self.add_section("scenes", "Light scenes", scenes)
        self.add_section("display", "False colours", self._build_display())
        # Below the table and the legend: the image grows when it is drawn (after a delay),
        # which must not push what is above it out of view.
        self.plan_view = plan_view.section(self)  # grid plan view (taskpanels/plan_view.py)
        plan = QtGui.QVBoxLayout()
        plan.addWidget(self.plan_view)
        self.add_section("plan", "Plan view", plan)
        self.study_view = study_view.section(self)  # accuracy vs time (taskpanels/study_view.py)
        study = QtGui.QVBoxLayout()
        study.addWidget(self.study_view)
        self.add_section("study", "Accuracy vs time", study)
        self.add_section("log", "Log", self._build_log())

    def add_section(self, name: str, title: str, content: QtGui.QLayout,
                    before: Optional[str] = None) -> QtGui.QGroupBox:
        """Add a titled section to the scrolling body (at the end, or before section
        ``before``); returns its group box. Other panels' parts plug in here."""
        box = QtGui.QGroupBox(title)
        content.setContentsMargins(4, 4, 4, 4)  # every pixel of width counts here
        box.setLayout(content)
        names = list(self.sections)
        index = names.index(before) if before in self.sections else len(names)
        self.body_layout.insertWidget(index, box)  # the body's stretch stays last
        items = list(self.sections.items())
        items.insert(index, (name, box))
        self.sections = dict(items)
        return box

    def _build_header(self) -> QtGui.QWidget:
        """Action buttons (two per row), progress bar and status: always in view."""
        header = QtGui.QWidget()
        grid = QtGui.QGridLayout(header)
        grid.setContentsMargins(0, 0, 0, 0)
        self.buttons: Dict[str, QtGui.QPushButton] = {}
        for index, (name, text, tip) in enumerate((
                ("check", "Check", "Check the model: luminaires, targets, geometry"),
                ("run", "Run", "Check, export and solve (in the background)"),
                ("export", "Export", "Write the scene file for the lightsolver CLI"),
                ("cancel", "Cancel", "Stop the solver; partial results are kept"))):
            button = QtGui.QPushButton(text)
            button.setToolTip(tip)
            button.setMinimumWidth(60)
            grid.addWidget(button, index // 2, index % 2)
            self.buttons[name] = button
        self.buttons["check"].clicked.connect(self.check)
        self.buttons["export"].clicked.connect(self.export)
        self.buttons["run"].clicked.connect(self.run)
        self.buttons["cancel"].clicked.connect(self.cancel)
        self.buttons["cancel"].setEnabled(False)
        self.progress = QtGui.QProgressBar()
        self.progress.setRange(0, 1000)
        self.progress.setValue(0)
        grid.addWidget(self.progress, 2, 0, 1, 2)
        self.status = QtGui.QLabel(f"Status: {self.analysis.Status}")
        self.status.setWordWrap(True)
        grid.addWidget(self.status, 3, 0, 1, 2)
        # Whether the stored results still describe the model (solver/store.results_state).
        self.state_label = QtGui.QLabel("")
        self.state_label.setWordWrap(True)
        grid.addWidget(self.state_label, 4, 0, 1, 2)
        return header

    def _build_settings(self) -> QtGui.QLayout:
        form = stacked_form()
        self.photons = QtGui.QSpinBox()
        self.photons.setRange(1, 2_000_000_000)
        self.photons.setSingleStep(100000)
        self.photons.setGroupSeparatorShown(True)
        self.photons.setValue(int(self.analysis.Photons))
        self.accuracy = QtGui.QDoubleSpinBox()
        self.accuracy.setRange(0.0, 50.0)
        self.accuracy.setSuffix(" %")
        self.accuracy.setSpecialValueText("off (fixed photons)")
        self.accuracy.setValue(float(self.analysis.TargetAccuracy) * 100.0)
        self.accuracy.setToolTip("Stop when every target's confidence interval is this "
                                 "narrow (relative half width); off: trace all photons")
        self.decide = QtGui.QCheckBox("Decide requirements")
        self.decide.setChecked(bool(getattr(self.analysis, "Decide", False)))
        self.decide.setToolTip("Trace until every requirement is pass or fail from its interval "
                               "(Photons is then the budget; undecided ones say what deciding "
                               "would cost)")
        # With Decide on the field is a budget, not what is traced: its label says so.
        self.photons_label = QtGui.QLabel("Photons")
        form.addRow(self.photons_label, self.photons)
        form.addRow("Target accuracy", self.accuracy)
        form.addRow(self.decide)
        self.decide.toggled.connect(self._label_photons)
        self.accuracy.valueChanged.connect(self._label_photons)
        self._label_photons()
        return form

    def _label_photons(self, *args: Any) -> None:
        budget = self.decide.isChecked() and self.accuracy.value() <= 0.0
        self.photons_label.setText("Photon budget" if budget else "Photons")
        self.photons.setToolTip("At most this many photons: the run stops as soon as every "
                                "requirement is decided" if budget else
                                "Photons traced (exactly)")

    def _build_results(self) -> QtGui.QLayout:
        """The table, "All columns" and the run's facts (taskpanels/results_table.py)."""
        layout = QtGui.QVBoxLayout()
        self.results_view = ResultsTable()
        layout.addWidget(self.results_view)
        # The widgets by their former names: scripts and the GUI scenarios use them.
        self.table = self.results_view.table
        self.all_columns = self.results_view.all_columns
        self.facts = self.results_view.facts
        return layout

    def _build_display(self) -> QtGui.QLayout:
        """Map, scale, legend and whether the scale is locked (taskpanels/display_view.py)."""
        layout = QtGui.QVBoxLayout()
        self.display_view = DisplayView(self.analysis, self._display_changed)
        layout.addWidget(self.display_view)
        view = self.display_view
        self.colour_map, self.scale_mode = view.colour_map, view.scale_mode
        self.scale_min, self.scale_max, self.legend = view.scale_min, view.scale_max, view.legend
        return layout

    def _build_log(self) -> QtGui.QLayout:
        layout = QtGui.QVBoxLayout()
        self.log_view = QtGui.QPlainTextEdit()
        self.log_view.setReadOnly(True)
        self.log_view.setMaximumHeight(120)
        # The log holds text tables: unwrapped they stay readable (scrolling sideways).
        self.log_view.setLineWrapMode(QtGui.QPlainTextEdit.NoWrap)
        layout.addWidget(self.log_view)
        return layout

    def _layout_table(self, *args: Any) -> None:
        self.results_view.layout_table()

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
        self.decide_view.set_running(running)

    def _write_settings(self) -> None:
        # One "Lighting settings" undo step only when a value really changes.
        store.write_settings(self.analysis, Photons=self.photons.value(),
                             TargetAccuracy=self.accuracy.value() / 100.0,
                             Decide=self.decide.isChecked())

    def show_live(self) -> None:
        """A live frame was stored (commands/live.py): the table and Status follow it."""
        try:
            self._set_status(self.analysis.Status)
            self._show_stored_results()
        except Exception:  # noqa: BLE001 - the panel was closed or the analysis deleted
            pass

    def show_state(self, state: Optional[Any] = None) -> None:
        """Show whether the stored results are current or stale (red, with what changed)."""
        try:
            state = state or store.results_state(self.analysis)
            stale = state.state in ("stale", "unknown")
            self.state_label.setText(state.text())
            self.state_label.setStyleSheet("color: #c62828; font-weight: bold;" if stale else "")
        except Exception:  # noqa: BLE001 - the panel was closed or the analysis deleted
            pass

    def _display_changed(self) -> None:
        """The user changed the map or the scale (the document and 3D view already follow)."""
        self.plan_view.render()

    def refresh(self) -> None:
        """Show the document's state: settings, results, verdicts, costs, scale (called on any
        document change by the Lighting document observer, and after a run)."""
        try:
            self._show_settings()
            self._show_stored_results()
        except Exception:  # noqa: BLE001 - the panel was closed or the analysis deleted
            pass

    def _document_settings(self) -> Dict[str, Any]:
        a = self.analysis
        return {"Photons": int(a.Photons), "TargetAccuracy": float(a.TargetAccuracy) * 100.0,
                "Decide": bool(getattr(a, "Decide", False))}

    def _show_settings(self) -> None:
        """Set the run settings whose document value changed since the last look (an Undo
        of "Lighting settings", a script, a Decide click); a value the user is typing, which
        reaches the document only with Check/Run/Export, survives unrelated changes (a
        luminaire moved, a results object stored)."""
        now = self._document_settings()
        fields = {"Photons": (self.photons, self.photons.setValue),
                  "TargetAccuracy": (self.accuracy, self.accuracy.setValue),
                  "Decide": (self.decide, self.decide.setChecked)}
        for name, value in now.items():
            widget, setter = fields[name]
            shown = widget.isChecked() if name == "Decide" else widget.value()
            if self._seen.get(name) != value and shown != value:
                widget.blockSignals(True)  # showing the document must not write it back
                setter(value)
                widget.blockSignals(False)
        self._seen = now
        self._label_photons()

    def _show_stored_results(self) -> None:
        result = store.load_from_document(self.analysis)
        self.plan_view.refresh()
        self.scene_view.refresh()
        self.display_view.refresh(result is not None)
        self.show_state()
        facts = facts_text(result) if result is not None else ""
        self.results_view.show_result(result, facts)
        self.decide_view.refresh(result, running=self.is_busy())

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

    def decide_now(self, budget: int) -> None:
        """One click on Decide: Decide on, no accuracy goal, ``budget`` photons at most, run."""
        if self.is_busy():
            return
        self.photons.setValue(int(budget))
        self.accuracy.setValue(0.0)
        self.decide.setChecked(True)
        self.log("info", f"Decide: tracing until every requirement is decided, at most "
                         f"{budget:,} photons")
        self.run()

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
        # What was traced and how long the whole run took (check, export, tracing, storing).
        traced = max(job.photons_traced, int(result.photons))  # both passes of a continued run
        went_on = ", continued by itself to decide" if job.continued else ""
        self._set_status(f"{self.analysis.Status} - {traced:,.0f} photons traced{went_on}, "
                         f"run took {seconds_text(job.wall_seconds())}")
        self.log("info", "Results:\n" + result.table())
        self.log("info", store.summary_line(result))  # last: the status bar shows this line
        self._show_stored_results()
        self.scroll.ensureWidgetVisible(self.table)
        FreeCADGui.updateGui()

    # -- task dialog protocol -------------------------------------------------------------
    def getStandardButtons(self) -> int:  # noqa: N802 (FreeCAD API name)
        return int(QtGui.QDialogButtonBox.Close)

    def needsFullSpace(self) -> bool:  # noqa: N802 (FreeCAD API name)
        """Take the task view's height: the body scrolls inside it, the header stays."""
        return True

    def is_busy(self) -> bool:
        """True while a run of this panel is in progress."""
        return self.job is not None and not self.job.finished

    def reject(self) -> bool:
        """Close: cancel a running solve first (waits briefly for the worker)."""
        if self.job is not None and not self.job.finished:
            self.job.cancel()
            self.job.wait(5.0)
        self.timer.stop()
        self.close_dialog()
        return True

    def accept(self) -> bool:
        return self.reject()
