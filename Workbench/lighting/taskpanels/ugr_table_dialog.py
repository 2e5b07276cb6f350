# SPDX-License-Identifier: LGPL-2.1-or-later
"""The UGR table of a photometric file (CIE 190 tabular method, docs/glare.md) in its own
dialog, laid out as data sheets print it: 19 rooms X x Y (2H..12H), five reflectance columns
(ceiling / walls / floor), viewed crosswise and endwise. Twelve columns do not fit the 264 px
combo view, so the luminaire chooser opens this window beside it."""
from __future__ import annotations

from typing import Any, List, Optional

from PySide import QtCore, QtGui

from lighting.luminaire_library import ugr_table_note as table_note
from lighting.luminaire_library import ugr_table_texts as cell_texts

GROUP_BACKGROUND = QtGui.QColor(232, 238, 244)


class UgrTableDialog(QtGui.QDialog):
    """A non-modal window with one file's UGR table."""

    def __init__(self, name: str, table: Any, parent: Optional[QtGui.QWidget] = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(f"UGR table - {name}")
        self.table = table
        layout = QtGui.QVBoxLayout(self)
        title = QtGui.QLabel(f"<b>UGR table of {name}</b> (CIE 190); column heads: "
                             "reflectances of ceiling, walls, floor")
        title.setWordWrap(True)
        layout.addWidget(title)
        self.grid = QtGui.QTableWidget(0, 12)
        self._fill()
        layout.addWidget(self.grid)
        self.note = QtGui.QLabel(table_note(table))
        self.note.setWordWrap(True)
        layout.addWidget(self.note)
        buttons = QtGui.QDialogButtonBox(QtGui.QDialogButtonBox.Close)
        buttons.rejected.connect(self.reject)
        layout.addWidget(buttons)
        self._fit()

    def _fill(self) -> None:
        grid = self.grid
        refl = [f"{c:.2f}\n{w:.2f}\n{f:.2f}" for c, w, f in self.table.reflectances]
        grid.setHorizontalHeaderLabels(["X", "Y"] + refl + refl)
        grid.horizontalHeader().setToolTip("Reflectances: ceiling, walls, floor")
        grid.verticalHeader().hide()
        grid.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        rows = cell_texts(self.table)
        grid.setRowCount(len(rows) + 1)
        for r, texts in enumerate(rows, start=1):
            for c, text in enumerate(texts):
                item = QtGui.QTableWidgetItem(text)
                item.setTextAlignment((QtCore.Qt.AlignRight if c >= 2 else QtCore.Qt.AlignLeft)
                                      | QtCore.Qt.AlignVCenter)
                grid.setItem(r, c, item)
        grid.resizeColumnsToContents()
        # After the resize: a spanning title would widen its first column alone.
        # Row 0: the two viewing directions over their five columns each.
        for column, text in ((0, "Room"), (2, "Viewed crosswise"), (7, "Viewed endwise")):
            item = QtGui.QTableWidgetItem(text)
            item.setTextAlignment(QtCore.Qt.AlignCenter)
            item.setBackground(GROUP_BACKGROUND)
            font = item.font()
            font.setBold(True)
            item.setFont(font)
            grid.setItem(0, column, item)
        grid.setSpan(0, 0, 1, 2)
        grid.setSpan(0, 2, 1, 5)
        grid.setSpan(0, 7, 1, 5)
        grid.resizeRowsToContents()

    def _fit(self) -> None:
        """Wide and tall enough to show the whole table without scrolling."""
        grid = self.grid
        width = grid.verticalHeader().width() + 4 + sum(
            grid.columnWidth(c) for c in range(grid.columnCount()))
        height = grid.horizontalHeader().height() + 4 + sum(
            grid.rowHeight(r) for r in range(grid.rowCount()))
        grid.setMinimumSize(width, height)
        self.note.setMaximumWidth(width)

    def texts(self) -> List[List[str]]:
        """The table as shown, row by row (scripts and the GUI scenario)."""
        grid = self.grid
        return [[grid.item(r, c).text() if grid.item(r, c) else ""
                 for c in range(grid.columnCount())] for r in range(grid.rowCount())]
