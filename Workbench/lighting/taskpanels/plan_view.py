# SPDX-License-Identifier: LGPL-2.1-or-later
"""Plan view of a calculation grid in the analysis task panel (GUI).

A section with a choice of the analysis' grids, the grid's image as lighting.plots draws it
(false colours, iso-lux lines, cell values where they fit, Em/Emin/U0 and the axes in
metres) rendered for the section's width, and *Save PNG...*. The analysis panel appends
``section(panel)`` and calls its ``refresh()`` when its results or colours change."""
from __future__ import annotations

from typing import Any, List, Optional

import FreeCAD
from PySide import QtCore, QtGui

from lighting import plots
from lighting.objects import analysis as analysis_mod

#: Narrowest image rendered (px): the default combo view leaves about 200 px.
MIN_WIDTH_PX = 200
#: Delay before re-rendering after a resize or new results (ms): one render per drag.
RESIZE_DELAY_MS = 200


def grid_targets(analysis: Any) -> List[Any]:
    """The analysis' grid targets, in its order."""
    return [t for t in analysis_mod.targets(analysis) if getattr(t, "TargetType", "") == "Grid"]


class PlanImage(QtGui.QLabel):
    """The rendered plan view; asks its section to re-render when its width changes."""

    resized = QtCore.Signal()

    def __init__(self, parent: Optional[QtGui.QWidget] = None) -> None:
        super().__init__(parent)
        self.setAlignment(QtCore.Qt.AlignCenter)
        self.setMinimumWidth(MIN_WIDTH_PX // 2)
        self.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Preferred)
        self._last_width = 0

    def resizeEvent(self, event: Any) -> None:  # noqa: N802 (Qt API name)
        super().resizeEvent(event)
        if abs(self.width() - self._last_width) > 8:
            self._last_width = self.width()
            self.resized.emit()


class PlanView(QtGui.QWidget):
    """The plan-view section of an analysis panel (the panel gives it its titled box)."""

    def __init__(self, analysis: Any, parent: Optional[QtGui.QWidget] = None) -> None:
        super().__init__(parent)
        self.analysis = analysis
        layout = QtGui.QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        row = QtGui.QHBoxLayout()
        self.choice = QtGui.QComboBox()
        self.choice.setToolTip("Grid to show")
        self.choice.setSizeAdjustPolicy(QtGui.QComboBox.AdjustToMinimumContentsLengthWithIcon)
        self.choice.setMinimumContentsLength(8)
        self.save_button = QtGui.QPushButton("Save PNG...")
        self.save_button.setToolTip("Write this plan view to a PNG file (for a report)")
        row.addWidget(self.choice, 1)
        row.addWidget(self.save_button)
        layout.addLayout(row)
        self.image = PlanImage()
        layout.addWidget(self.image)
        self.png: bytes = b""
        self._timer = QtCore.QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(RESIZE_DELAY_MS)
        self._timer.timeout.connect(self.render)
        self.image.resized.connect(self._timer.start)
        self.choice.currentIndexChanged.connect(lambda *_: self.render())
        self.save_button.clicked.connect(self.save)

    # -- content ---------------------------------------------------------------------------
    def target(self) -> Optional[Any]:
        """The grid chosen, or None."""
        name = self.choice.currentData()
        return self.analysis.Document.getObject(name) if name else None

    def refresh(self) -> None:
        """List the analysis' grids again (keeping the choice) and re-render soon: drawing
        takes a few hundred ms, which must not hold up the panel's opening or a run's start."""
        current = self.choice.currentData()
        self.choice.blockSignals(True)
        self.choice.clear()
        for grid in grid_targets(self.analysis):
            self.choice.addItem(grid.Label, grid.Name)
        index = self.choice.findData(current) if current else -1
        self.choice.setCurrentIndex(max(index, 0) if self.choice.count() else -1)
        self.choice.blockSignals(False)
        self._timer.start()

    def render(self) -> None:
        """Draw the chosen grid's plan view at the section's width (a note without results)."""
        target = self.target()
        data = plots.grid_plot_data(self.analysis, target) if target is not None else None
        self.save_button.setEnabled(data is not None)
        if data is None:
            self.png = b""
            self.image.setPixmap(QtGui.QPixmap())
            self.image.setMinimumHeight(0)
            self.image.setText("No grid results yet: add a grid and press Run."
                               if target is None or not self.choice.count()
                               else f"'{target.Label}' has no results yet: press Run.")
            self.image.setWordWrap(True)
            return
        width = max(self.image.width(), MIN_WIDTH_PX)
        try:
            self.png = plots.grid_png(data, plots.analysis_scale(self.analysis), width_px=width)
        except Exception as exc:  # noqa: BLE001 - a plot must never break the panel
            FreeCAD.Console.PrintWarning(f"Lighting: cannot draw the plan view: {exc}\n")
            self.image.setText(f"Cannot draw the plan view: {exc}")
            return
        pixmap = QtGui.QPixmap()
        pixmap.loadFromData(self.png, "PNG")
        self.image.setPixmap(pixmap)
        # Task boxes keep the height they had when shown: ask for the image's.
        self.image.setMinimumHeight(pixmap.height())
        self.updateGeometry()

    def save(self) -> Optional[str]:
        """Ask for a file name and write the plan view there (full size)."""
        target = self.target()
        if target is None:
            return None
        path, _ = QtGui.QFileDialog.getSaveFileName(
            self, "Save plan view", f"{target.Label}.png", "PNG images (*.png)")
        if not path:
            return None
        try:
            plots.save_grid_png(target, path, analysis=self.analysis)
        except (OSError, ValueError) as exc:
            QtGui.QMessageBox.warning(self, "Lighting", f"Cannot save the plan view:\n{exc}")
            return None
        FreeCAD.Console.PrintMessage(f"Lighting: plan view written to {path}\n")
        return path


def section(panel: Any) -> PlanView:
    """The plan-view section for an analysis task panel (``panel.analysis``)."""
    return PlanView(panel.analysis)
