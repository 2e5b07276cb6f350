# SPDX-License-Identifier: LGPL-2.1-or-later
"""The analysis panel's results section: the table (target, Em, U0 and the verdict in the narrow
panel; the intervals, Emin and Emax behind "All columns" and in each row's tooltip) and the run's
facts under it: photons traced, how long it took, why the run stopped."""
from __future__ import annotations

from typing import Any, List, Optional, Tuple

from PySide import QtCore, QtGui

from lighting.solver import results as results_mod

COLUMNS = ("Target", "Type", "Em lx", "Em CI", "Emin lx", "Emin CI", "Emax lx", "Emax CI",
           "U0", "U0 CI", "Check")
#: The columns shown in the narrow default panel (the others: "All columns", tooltips).
ESSENTIAL_COLUMNS = ("Target", "Em lx", "U0", "Check")
#: Text colours of the verdict column: pass green, FAIL red, undecided amber.
VERDICT_COLOURS = {"pass": (0, 130, 0), "FAIL": (200, 0, 0), "undecided": (190, 110, 0)}
#: The verdict of an observer without a UGR limit: said, not left blank.
NO_LIMIT = "no limit set"


def _ci(pair: Optional[Tuple[float, float]], digits: int = 1) -> str:
    return results_mod.interval_text(pair, digits, " - ")


def rows(result: results_mod.AnalysisResult) -> List[List[str]]:
    """The table's rows, one per target, in COLUMNS order."""
    out = []
    for t in result.targets:
        verdict = t.verdict_text()
        ci = _ci((t.ci_low_lux, t.ci_high_lux))
        if t.kind == "grid":
            out.append([t.label, t.kind, f"{t.mean_lux:.1f}", ci, f"{t.min_lux:.1f}",
                        _ci(t.min_ci_lux), f"{t.max_lux:.1f}", _ci(t.max_ci_lux),
                        f"{t.uniformity:.2f}", _ci(t.uniformity_ci, 2), verdict])
        elif t.is_glare:  # the Em columns show its (max) UGR
            out.append([t.label, t.kind, *t.ugr_text()] + ["-"] * 6 + [verdict or NO_LIMIT])
        else:
            out.append([t.label, t.kind, f"{t.mean_lux:.1f}", ci] + ["-"] * 6 + [verdict])
    return out


def seconds_text(seconds: float) -> str:
    """A duration a person reads: "40 ms", "2.3 s", "1 min 05 s" (never "0.00 s")."""
    if seconds < 1.0:
        return f"{max(seconds * 1000.0, 1.0):.0f} ms"
    if seconds < 60.0:
        return f"{seconds:.1f} s"
    return f"{int(seconds // 60)} min {int(seconds % 60):02d} s"


def undecided_count(result: results_mod.AnalysisResult) -> int:
    """How many requirements of the shown results (a light scene's rescaled ones included)
    are undecided."""
    return sum(len(t.undecided) for t in result.targets if not t.estimated)


def facts_text(result: results_mod.AnalysisResult, wall_seconds: Optional[float] = None) -> str:
    """The run's facts, all from the results: the photons traced (of the run's budget, when a
    goal stopped it earlier), the time the tracing took (or ``wall_seconds``), the confidence
    level and why it stopped. "every requirement decided" only when none shown is undecided:
    a light scene's rescaled row can be undecided after a run that decided the traced one."""
    traced = f"{result.photons:,.0f}".replace(",", "\u202f")
    text = f"{traced} photons traced"
    budget = int(result.photons_requested)
    if budget and budget > result.photons:
        text += f" (budget {budget:,})".replace(",", "\u202f")
    seconds = wall_seconds if wall_seconds is not None else result.seconds
    text += f" in {seconds_text(seconds)}, {result.confidence * 100:g} % confidence intervals"
    undecided = undecided_count(result)
    judged = any(t.verdict is not None for t in result.targets if not t.estimated)
    if result.partial:
        text += " - PARTIAL (cancelled)"
    elif undecided:
        text += f" - {undecided} requirement(s) undecided: see Undecided below"
    elif judged:
        text += " - every requirement decided"
        if result.stop_reason == "decided" and budget and budget > result.photons:
            text += ", so the run stopped before its budget"
    return text


class ResultsTable(QtGui.QWidget):
    """The results table, its "All columns" switch and the run's facts."""

    def __init__(self, parent: Optional[QtGui.QWidget] = None) -> None:
        super().__init__(parent)
        layout = QtGui.QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
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
        self.all_columns.toggled.connect(self.layout_table)
        layout.addWidget(self.all_columns)
        self.facts = QtGui.QLabel("")
        self.facts.setWordWrap(True)
        layout.addWidget(self.facts)
        self.layout_table()

    def show_result(self, result: Optional[results_mod.AnalysisResult], facts: str) -> None:
        """Fill the table from ``result`` (empty: "No results yet") with ``facts`` under it."""
        self.table.setRowCount(0)
        if result is None:
            self.layout_table()
            self.facts.setText("No results yet: press Run.")
            return
        for row, values in enumerate(rows(result)):
            self.table.insertRow(row)
            tip = "\n".join(f"{name}: {value}" for name, value in zip(COLUMNS, values))
            for column, value in enumerate(values):
                item = QtGui.QTableWidgetItem(value)
                item.setToolTip(tip)
                colour = VERDICT_COLOURS.get(value.split(" ")[0]) \
                    if column == len(values) - 1 else None
                if colour is not None:
                    item.setForeground(QtGui.QBrush(QtGui.QColor(*colour)))
                self.table.setItem(row, column, item)
        self.layout_table()
        self.facts.setText(facts)

    def layout_table(self, *args: Any) -> None:
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
