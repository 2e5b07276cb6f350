# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of an analysis: Check / Export / Run / Cancel with a progress bar, the colour
scale, the results table (Em, Emin, Emax, U0 with CIs) and a log. It fits FreeCAD's default
combo view (about 264 px): a fixed header with the buttons, sections that scroll below it
(``add_section``); it is modeless, so the toolbars stay usable while it is open.

Check and the scene export run on the GUI thread (the export keeps the event loop turning);
the solver runs on a worker thread that a QTimer polls, so the GUI stays responsive and
Cancel works. Results are applied on the GUI thread in one undo step."""
from __future__ import annotations

from typing import Any, Dict, List, Optional, Tuple

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from lighting.messages import CheckError, LightingError
from lighting.objects.analysis import COLOR_MAPS, SCALE_MODES
from lighting.solver import machine, results as results_mod, store
from lighting.taskpanels import light_scene_view, plan_view, study_view
from lighting.taskpanels.legend_widget import LegendWidget
from lighting.taskpanels.modeless import ModelessPanel
from lighting.viewproviders import coloring
from lighting.viewproviders.base import icon_path

POLL_MS = 100
COLUMNS = ("Target", "Type", "Em lx", "Em CI", "Emin lx", "Emin CI", "Emax lx", "Emax CI",
           "U0", "U0 CI", "Check")
#: The columns shown in the narrow default panel (the others: "All columns", tooltips).
ESSENTIAL_COLUMNS = ("Target", "Em lx", "U0", "Check")

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


#: Text colours of the verdict column: pass green, FAIL red, undecided amber.
VERDICT_COLOURS = {"pass": (0, 130, 0), "FAIL": (200, 0, 0), "undecided": (190, 110, 0)}


def _ci(pair: Optional[Tuple[float, float]], digits: int = 1) -> str:
    return results_mod.interval_text(pair, digits, " - ")


def _rows(result: results_mod.AnalysisResult) -> List[List[str]]:
    rows = []
    for t in result.targets:
        verdict = t.verdict_text()
        ci = _ci((t.ci_low_lux, t.ci_high_lux))
        if t.kind == "grid":
            rows.append([t.label, t.kind, f"{t.mean_lux:.1f}", ci, f"{t.min_lux:.1f}",
                         _ci(t.min_ci_lux), f"{t.max_lux:.1f}", _ci(t.max_ci_lux),
                         f"{t.uniformity:.2f}", _ci(t.uniformity_ci, 2), verdict])
        elif t.is_glare:  # the Em columns show its (max) UGR
            rows.append([t.label, t.kind, *t.ugr_text()] + ["-"] * 6 + [verdict])
        else:
            rows.append([t.label, t.kind, f"{t.mean_lux:.1f}", ci] + ["-"] * 6 + [verdict])
    return rows


def _stacked_form() -> QtGui.QFormLayout:
    """A form whose rows put the label above the field when the panel is narrow."""
    form = QtGui.QFormLayout()
    form.setRowWrapPolicy(QtGui.QFormLayout.WrapLongRows)
    form.setFieldGrowthPolicy(QtGui.QFormLayout.AllNonFixedFieldsGrow)
    return form


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
        self._seen = self._document_fields()  # what refresh() compares against
        self._show_stored_results()
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
        self.add_section("results", "Results (maintained illuminance)", self._build_results())
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
        form = _stacked_form()
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
        form.addRow("Photons", self.photons)
        form.addRow("Target accuracy", self.accuracy)
        form.addRow(self.decide)
        return form

    def _build_results(self) -> QtGui.QLayout:
        """The essentials (target, Em, U0, verdict) fit the narrow panel; the confidence
        intervals, Emin and Emax are in each row's tooltip and behind "All columns"."""
        layout = QtGui.QVBoxLayout()
        self.table = QtGui.QTableWidget(0, len(COLUMNS))
        self.table.setHorizontalHeaderLabels(list(COLUMNS))
        self.table.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        self.table.verticalHeader().setVisible(False)
        self.table.setTextElideMode(QtCore.Qt.ElideRight)
        self.table.setWordWrap(False)
        self.table.setVerticalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        layout.addWidget(self.table)
        self.all_columns = QtGui.QCheckBox("All columns")
        self.all_columns.setToolTip("Show the confidence intervals, Emin and Emax too")
        self.all_columns.toggled.connect(self._layout_table)
        layout.addWidget(self.all_columns)
        self.facts = QtGui.QLabel("")
        self.facts.setWordWrap(True)
        layout.addWidget(self.facts)
        self._layout_table()
        return layout

    def _build_display(self) -> QtGui.QLayout:
        form = _stacked_form()
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
        form.addRow("Map", self.colour_map)
        form.addRow("Scale", self.scale_mode)
        form.addRow("Fixed min", self.scale_min)
        form.addRow("Fixed max", self.scale_max)
        self.legend = LegendWidget()
        form.addRow(self.legend)
        for widget in (self.colour_map, self.scale_mode):
            widget.currentIndexChanged.connect(self._display_changed)
        for widget in (self.scale_min, self.scale_max):
            widget.valueChanged.connect(self._display_changed)
        return form

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
        """Show the essential columns (or all), the target column taking the spare width,
        and make the table as tall as its rows: the panel scrolls, not the table."""
        table = self.table
        every = self.all_columns.isChecked()
        header = table.horizontalHeader()
        for column, name in enumerate(COLUMNS):
            table.setColumnHidden(column, not every and name not in ESSENTIAL_COLUMNS)
            header.setSectionResizeMode(column, QtGui.QHeaderView.ResizeToContents)
        if not every:
            header.setSectionResizeMode(0, QtGui.QHeaderView.Stretch)
        table.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAsNeeded if every
                                           else QtCore.Qt.ScrollBarAlwaysOff)
        table.resizeRowsToContents()
        height = header.height() + 2 * table.frameWidth()
        height += sum(table.rowHeight(r) for r in range(table.rowCount()))
        if every:
            height += table.horizontalScrollBar().sizeHint().height()
        table.setFixedHeight(max(height, header.height() + 2 * table.frameWidth() + 4))

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

    def refresh(self) -> None:
        """Show the document's state again: taskpanels/sync.py calls this after any change of
        the document, Undo and Redo included. The fields the document changed, Status, and
        the table, legend and verdicts from the results object."""
        if not self.is_busy():
            self._set_status(self.analysis.Status)
        self._follow_fields()
        self._show_stored_results()

    def _document_fields(self) -> Dict[str, Any]:
        a = self.analysis
        return {"Photons": int(a.Photons), "TargetAccuracy": float(a.TargetAccuracy),
                "Decide": bool(getattr(a, "Decide", False)), "ColorMap": a.ColorMap,
                "ScaleMode": a.ScaleMode, "ScaleMinLux": float(a.ScaleMinLux),
                "ScaleMaxLux": float(a.ScaleMaxLux)}

    def _follow_fields(self) -> None:
        """Set the fields whose document value changed since the last look (an Undo of
        "Lighting settings"); a value the user is typing survives unrelated changes."""
        now = self._document_fields()
        setters = {"Photons": (self.photons, lambda v: self.photons.setValue(v)),
                   "TargetAccuracy": (self.accuracy,
                                      lambda v: self.accuracy.setValue(v * 100.0)),
                   "Decide": (self.decide, self.decide.setChecked),
                   "ColorMap": (self.colour_map, self.colour_map.setCurrentText),
                   "ScaleMode": (self.scale_mode, self.scale_mode.setCurrentText),
                   "ScaleMinLux": (self.scale_min, self.scale_min.setValue),
                   "ScaleMaxLux": (self.scale_max, self.scale_max.setValue)}
        for name, value in now.items():
            if self._seen.get(name) != value:
                widget, setter = setters[name]
                widget.blockSignals(True)  # showing the document must not write it back
                setter(value)
                widget.blockSignals(False)
        self._seen = now

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
        self.plan_view.render()

    def _show_stored_results(self) -> None:
        result = store.load_from_document(self.analysis)
        self.plan_view.refresh()
        self.scene_view.refresh()
        fixed = self.analysis.ScaleMode == "Fixed"
        self.scale_min.setEnabled(fixed)
        self.scale_max.setEnabled(fixed)
        self.legend.set_scale(coloring.scale_for(self.analysis) if result else None)
        self.table.setRowCount(0)
        self.show_state()
        if result is None:
            self._layout_table()
            self.facts.setText("No results yet: press Run.")
            return
        for row, values in enumerate(_rows(result)):
            self.table.insertRow(row)
            tip = "\n".join(f"{name}: {value}" for name, value in zip(COLUMNS, values))
            for column, value in enumerate(values):
                item = QtGui.QTableWidgetItem(value)
                item.setToolTip(tip)
                colour = VERDICT_COLOURS.get(value.split(" ")[0]) if column == len(values) - 1 \
                    else None
                if colour is not None:
                    item.setForeground(QtGui.QBrush(QtGui.QColor(*colour)))
                self.table.setItem(row, column, item)
        self._layout_table()
        facts = (f"{result.photons:.0f} photons, {result.seconds:.2f} s, "
                 f"{result.confidence * 100:g} % confidence intervals")
        if result.partial:
            facts += " - PARTIAL (cancelled)"
        elif result.stop_reason == "decided":
            facts += " - every requirement decided"
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
