# SPDX-License-Identifier: LGPL-2.1-or-later
"""The analysis panel's "Accuracy vs time" section: runs ``lightsolver study`` on the
analysis' scene on a worker thread (the GUI keeps turning) and shows its plot (per-cell
interval width against seconds, log-log, with the N^-1/2 line) and the photons and seconds
each per-cell accuracy needs (lighting/solver/study.py)."""
from __future__ import annotations

import threading
from typing import Any, Optional

from PySide import QtCore, QtGui

from lighting.solver import study as study_mod

POLL_MS = 100


class StudyView(QtGui.QWidget):
    """Button, budget, plot and goals of an analysis' accuracy study."""

    def __init__(self, analysis: Any, parent: Optional[QtGui.QWidget] = None) -> None:
        super().__init__(parent)
        self.analysis = analysis
        self.result: Optional[study_mod.StudyResult] = None
        self.error: Optional[str] = None
        self._thread: Optional[threading.Thread] = None
        layout = QtGui.QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        self.max_photons = QtGui.QSpinBox()
        self.max_photons.setRange(20_000, 1_000_000_000)
        self.max_photons.setSingleStep(100_000)
        self.max_photons.setGroupSeparatorShown(True)
        self.max_photons.setValue(study_mod.DEFAULT_MAX_PHOTONS)
        self.max_photons.setToolTip("Photons of the last checkpoint (doubling from 10 000)")
        self.button = QtGui.QPushButton("Study accuracy")
        self.button.setToolTip("One run with doubling checkpoints: what each per-cell accuracy "
                               "costs in photons and seconds for this scene")
        self.button.clicked.connect(self.start)
        layout.addWidget(QtGui.QLabel("Up to photons"))
        layout.addWidget(self.max_photons)
        layout.addWidget(self.button)
        self.image = QtGui.QLabel("")
        self.image.setAlignment(QtCore.Qt.AlignCenter)
        self.image.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Preferred)
        layout.addWidget(self.image)
        self.goals = QtGui.QLabel("")
        self.goals.setWordWrap(True)
        layout.addWidget(self.goals)
        self._timer = QtCore.QTimer(self)
        self._timer.setInterval(POLL_MS)
        self._timer.timeout.connect(self._poll)

    def start(self) -> None:
        """Export on the GUI thread (the document is read there), study on a worker."""
        from lighting import api

        if self._thread is not None:
            return
        try:
            scene_file = api.export_scene(self.analysis.Document, self.analysis)
        except Exception as exc:  # noqa: BLE001 - CheckError and friends: shown, not raised
            self._show_error(str(exc))
            return
        self.result, self.error = None, None
        budget = self.max_photons.value()
        self._thread = threading.Thread(target=self._work, args=(scene_file, budget),
                                        daemon=True)
        self.button.setEnabled(False)
        self.goals.setText("studying ...")
        self._thread.start()
        self._timer.start()

    def _work(self, scene_file: str, budget: int) -> None:
        try:
            self.result = study_mod.study_scene(scene_file, budget)
        except Exception as exc:  # noqa: BLE001 - reported on the GUI thread
            self.error = str(exc)

    def _poll(self) -> None:
        if self._thread is None or self._thread.is_alive():
            return
        self._timer.stop()
        self._thread = None
        self.button.setEnabled(True)
        if self.error is not None or self.result is None:
            self._show_error(self.error or "the study ended without results")
            return
        pixmap = QtGui.QPixmap(self.result.plot_file)
        width = max(self.image.width(), 180)
        if not pixmap.isNull():
            self.image.setPixmap(pixmap.scaledToWidth(width, QtCore.Qt.SmoothTransformation))
        self.goals.setText(self.result.goals_text())

    def _show_error(self, text: str) -> None:
        self.goals.setText(f"Study failed: {text}")
        self.goals.setStyleSheet("color: #c62828;")

    def busy(self) -> bool:
        """True while a study runs."""
        return self._thread is not None


def section(panel: Any) -> StudyView:
    """The study section for an analysis task panel (``panel.analysis``)."""
    return StudyView(panel.analysis)
