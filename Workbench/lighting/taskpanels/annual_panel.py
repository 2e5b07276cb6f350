# SPDX-License-Identifier: LGPL-2.1-or-later
"""The annual daylight panel (GUI): the weather file, Run (Check -> Prepare on the main thread,
the year traced on a worker thread, Results in one undo step: solver/annual.py), the map the
grids show, and the results in lines (sDA300/50% with its interval and verdicts, ASE, DA300,
UDI, EN 17037's levels, the weather file with its hash). The other settings are edited in the
property editor. ``lightsolver.annual`` cannot be stopped mid-trace: Cancel drops its results
when it returns (the panel says so)."""
from __future__ import annotations

from typing import Any, Optional

import FreeCAD
from PySide import QtCore, QtGui

from lighting.objects import annual as annual_mod
from lighting.taskpanels.modeless import ModelessPanel

POLL_MS = 200
_last_panel: Optional["AnnualPanel"] = None


def last_panel() -> Optional["AnnualPanel"]:
    """The panel opened last (GUI scenarios read it)."""
    return _last_panel


class AnnualPanel(ModelessPanel):
    """Run and read an annual daylight analysis; the model stays editable."""

    def __init__(self, annual: Any) -> None:
        global _last_panel
        self.annual = annual
        self.job: Optional[Any] = None
        self.last_job: Optional[Any] = None
        self.form = QtGui.QWidget()
        self.form.setWindowTitle("Annual daylight" if annual.Label == "Annual daylight"
                                 else f"Annual daylight: {annual.Label}")
        layout = QtGui.QVBoxLayout(self.form)
        row = QtGui.QHBoxLayout()
        self.weather = QtGui.QLineEdit(str(annual.WeatherFile))
        self.weather.setMinimumWidth(60)
        self.weather.setToolTip("The site's EnergyPlus weather file (.epw)")
        self.weather.editingFinished.connect(self._weather_edited)
        browse = QtGui.QPushButton("...")
        browse.clicked.connect(self._browse)
        row.addWidget(QtGui.QLabel("Weather"))
        row.addWidget(self.weather, 1)
        row.addWidget(browse)
        layout.addLayout(row)
        buttons = QtGui.QHBoxLayout()
        self.run_button = QtGui.QPushButton("Run")
        self.run_button.clicked.connect(self.run)
        self.cancel_button = QtGui.QPushButton("Cancel")
        self.cancel_button.setToolTip("The year's trace cannot be stopped: its results are "
                                      "dropped when it ends")
        self.cancel_button.clicked.connect(self.cancel)
        self.cancel_button.setEnabled(False)
        buttons.addWidget(self.run_button)
        buttons.addWidget(self.cancel_button)
        layout.addLayout(buttons)
        map_row = QtGui.QHBoxLayout()
        map_row.addWidget(QtGui.QLabel("Grids show"))
        self.map = QtGui.QComboBox()
        self.map.addItems(list(annual_mod.MAPS))
        self.map.currentIndexChanged.connect(self._map_chosen)
        map_row.addWidget(self.map, 1)
        layout.addLayout(map_row)
        self.status = QtGui.QLabel("")
        self.status.setWordWrap(True)
        layout.addWidget(self.status)
        # Read-only text that wraps anywhere: a file name or a hash is one long word, which a
        # wrapping label cannot break, so it widened the panel past the task view.
        self.lines = QtGui.QPlainTextEdit()
        self.lines.setReadOnly(True)
        self.lines.setLineWrapMode(QtGui.QPlainTextEdit.WidgetWidth)
        self.lines.setWordWrapMode(QtGui.QTextOption.WrapAtWordBoundaryOrAnywhere)
        self.lines.setMinimumHeight(320)
        layout.addWidget(self.lines, 1)
        self.timer = QtCore.QTimer()
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self._poll)
        _last_panel = self
        self.refresh()

    # -- document -> panel ----------------------------------------------------------------
    def refresh(self) -> None:
        """Show the object as the document holds it now."""
        from lighting.solver import annual as annual_run
        from lighting.taskpanels import sync

        if not sync.object_alive(self.annual):
            self.close_dialog()
            return
        obj = self.annual
        if self.weather.text() != str(obj.WeatherFile):
            self.weather.setText(str(obj.WeatherFile))
        self.map.blockSignals(True)
        self.map.setCurrentIndex(max(0, list(annual_mod.MAPS).index(str(obj.Map))))
        self.map.blockSignals(False)
        if self.job is None:
            current = annual_run.is_current(obj) if obj.SummaryJson else None
            state = {None: "", True: " (current)",
                     False: " (stale: the model or the weather file changed since)"}[current]
            self.status.setText(f"Status: {obj.Status}{state}")
        text = "\n".join(obj.SummaryLines)
        if self.lines.toPlainText() != text:
            self.lines.setPlainText(text)

    def _weather_edited(self) -> None:
        text = self.weather.text().strip()
        if text != str(self.annual.WeatherFile):
            self._write("WeatherFile", text)

    def _browse(self) -> None:
        import FreeCADGui

        path, _ = QtGui.QFileDialog.getOpenFileName(FreeCADGui.getMainWindow(),
                                                    "Weather file", self.weather.text(),
                                                    "EnergyPlus weather (*.epw)")
        if path:
            self.weather.setText(path)
            self._write("WeatherFile", path)

    def _map_chosen(self, index: int) -> None:
        self._write("Map", annual_mod.MAPS[index])

    def _write(self, prop: str, value: Any) -> None:
        from lighting.solver import store

        with store.undo_step(self.annual.Document, "Annual daylight settings"):
            setattr(self.annual, prop, value)

    # -- run --------------------------------------------------------------------------------
    def is_busy(self) -> bool:
        return self.job is not None

    def run(self) -> None:
        """Check and Prepare here, the trace on a worker thread (polled)."""
        from lighting.messages import LightingError
        from lighting.solver import annual as annual_run

        if self.job is not None:
            return
        def log(level: str, text: str) -> None:
            if level == "error":
                FreeCAD.Console.PrintError(f"Lighting: {text}\n")
            else:
                FreeCAD.Console.PrintMessage(f"Lighting: {text}\n")

        try:
            job = annual_run.AnnualRun(self.annual, log=log)
            self.status.setText("Checking ...")
            job.check()
            self.status.setText("Exporting the scene ...")
            job.prepare()
        except LightingError as exc:
            self.status.setText(f"Check failed:\n{exc}")
            return
        self.job = job
        job.start()
        self.run_button.setEnabled(False)
        self.cancel_button.setEnabled(True)
        warnings = [m.text for m in job.report.messages if m.level == "warning"]
        self.status.setText("\n".join([f"Tracing the year ({int(self.annual.Photons):,} "
                                        "photons) ..."] + [f"Warning: {w}" for w in warnings]))
        self.timer.start()

    def cancel(self) -> None:
        if self.job is not None:
            self.job.cancel()
            self.status.setText("Cancelling: the results are dropped when the trace ends ...")

    def _poll(self) -> None:
        job = self.job
        if job is None or not job.finished:
            return
        self.timer.stop()
        self.job = None
        self.run_button.setEnabled(True)
        self.cancel_button.setEnabled(False)
        if job.error is not None:
            text = job.fail(job.error)
            self.status.setText(f"Status: {self.annual.Status}")
            FreeCAD.Console.PrintError(f"Lighting: {text}\n")
        else:
            try:
                job.apply()
            except Exception as exc:  # noqa: BLE001 - shown, the document is left as it was
                self.status.setText(f"Failed: {job.fail(exc)}")
                return
        self.last_job = job
        self.refresh()

    # -- dialog -------------------------------------------------------------------------------
    def getStandardButtons(self) -> int:  # noqa: N802 (FreeCAD API name)
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self) -> bool:
        if self.job is not None:
            self.job.cancel()
        self.timer.stop()
        self.close_dialog()
        return True

    def accept(self) -> bool:
        return self.reject()
