# SPDX-License-Identifier: LGPL-2.1-or-later
"""The analysis panel's "False colours" section: the map, the scale (Requirements: 0 to 1.5 x
the highest required Em, the same for every run; Auto: from this run; Fixed: the user's), the
legend bar and a line that says whether the scale is locked and where it comes from."""
from __future__ import annotations

from typing import Any, Callable, Optional

from PySide import QtGui

from lighting import plots
from lighting.objects.analysis import COLOR_MAPS, SCALE_MODES
from lighting.taskpanels.legend_widget import LegendWidget
from lighting.viewproviders import coloring


def stacked_form() -> QtGui.QFormLayout:
    """A form whose rows put the label above the field when the panel is narrow."""
    form = QtGui.QFormLayout()
    form.setRowWrapPolicy(QtGui.QFormLayout.WrapLongRows)
    form.setFieldGrowthPolicy(QtGui.QFormLayout.AllNonFixedFieldsGrow)
    return form


class DisplayView(QtGui.QWidget):
    """Colour map and scale of an analysis; ``changed()`` after the user changed one."""

    def __init__(self, analysis: Any, changed: Callable[[], None],
                 parent: Optional[QtGui.QWidget] = None) -> None:
        super().__init__(parent)
        self.analysis = analysis
        self._changed = changed
        form = stacked_form()
        form.setContentsMargins(0, 0, 0, 0)
        self.setLayout(form)
        self.colour_map = QtGui.QComboBox()
        self.colour_map.addItems(list(COLOR_MAPS))
        self.colour_map.setCurrentText(analysis.ColorMap)
        self.scale_mode = QtGui.QComboBox()
        self.scale_mode.addItems(list(SCALE_MODES))
        self.scale_mode.setCurrentText(analysis.ScaleMode)
        self.scale_mode.setToolTip("Requirements: 0 to 1.5 x the highest required Em, the same "
                                   "for every run; Auto: 0 to this run's largest value; Fixed: "
                                   "your minimum and maximum")
        self.scale_min = QtGui.QDoubleSpinBox()
        self.scale_max = QtGui.QDoubleSpinBox()
        for box, value in ((self.scale_min, analysis.ScaleMinLux),
                           (self.scale_max, analysis.ScaleMaxLux)):
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
        self.lock = QtGui.QLabel("")
        self.lock.setWordWrap(True)
        form.addRow(self.lock)
        for widget in (self.colour_map, self.scale_mode):
            widget.currentIndexChanged.connect(self._edited)
        for widget in (self.scale_min, self.scale_max):
            widget.valueChanged.connect(self._edited)

    def _edited(self, *args: Any) -> None:
        a = self.analysis
        a.ColorMap = self.colour_map.currentText()
        a.ScaleMode = self.scale_mode.currentText()
        a.ScaleMinLux = self.scale_min.value()
        a.ScaleMaxLux = self.scale_max.value()
        self.refresh(True)
        coloring.refresh(a)
        self._changed()

    def refresh(self, has_results: bool) -> None:
        """Show the document's map and scale (the legend only with results) and the lock."""
        a = self.analysis
        for widget, text in ((self.colour_map, a.ColorMap), (self.scale_mode, a.ScaleMode)):
            if widget.currentText() != text:
                widget.blockSignals(True)
                widget.setCurrentText(text)
                widget.blockSignals(False)
        fixed = a.ScaleMode == "Fixed"
        self.scale_min.setEnabled(fixed)
        self.scale_max.setEnabled(fixed)
        self.legend.set_scale(coloring.scale_for(a) if has_results else None)
        locked, text = plots.scale_note(a)
        # Bold when locked (no font here draws a padlock glyph); amber when it follows runs.
        self.lock.setText(text)
        self.lock.setStyleSheet("font-weight: bold;" if locked else "color: #8a5a00;")
