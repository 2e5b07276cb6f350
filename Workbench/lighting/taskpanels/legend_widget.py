# SPDX-License-Identifier: LGPL-2.1-or-later
"""The analysis panel's colour scale: a horizontal bar with its minimum and maximum."""
from __future__ import annotations

from typing import Any, Optional

from PySide import QtGui

from lighting.colormap import Scale


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
