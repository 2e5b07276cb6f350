# SPDX-License-Identifier: LGPL-2.1-or-later
"""The analysis panel's results section: the table (per target its name on a line of its own
across the table, and under it Em, U0 and the verdict: what fits the narrow panel with every
name readable), each row's tooltip with every figure, its interval and the requirement judged,
"All columns": a details table under it with every figure and interval one per line (so the
panel never scrolls sideways at its default width), and the run's facts: photons traced, how
long it took, why the run stopped. An observer's row is its own: UGR with its interval and
limit, never an illuminance or an area."""
from __future__ import annotations

from typing import Any, List, Optional, Tuple

from PySide import QtCore, QtGui

from lighting import daylight_results
from lighting.solver import results as results_mod

COLUMNS = ("Target", "Type", "Em lx", "Em CI", "Emin lx", "Emin CI", "Emax lx", "Emax CI",
           "U0", "U0 CI", "Check")
#: The columns shown in the narrow default panel (the others: "All columns", tooltips); the
#: target's name is drawn as a line of its own above each row's values (NameAboveDelegate).
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
        if t.daylight_factor is not None:  # a DF grid: its DF in the Em columns
            value, interval = daylight_results.table_values(t.daylight_factor)
            out.append([t.label, "DF grid", value, interval] + ["-"] * 6 + [verdict])
        elif t.kind == "grid":
            out.append([t.label, t.kind, f"{t.mean_lux:.1f}", ci, f"{t.min_lux:.1f}",
                        _ci(t.min_ci_lux), f"{t.max_lux:.1f}", _ci(t.max_ci_lux),
                        f"{t.uniformity:.2f}", _ci(t.uniformity_ci, 2), verdict])
        elif t.is_glare:  # the Em columns show its (max) UGR
            out.append([t.label, t.kind, *t.ugr_text()] + ["-"] * 6 + [verdict or NO_LIMIT])
        else:
            out.append([t.label, t.kind, f"{t.mean_lux:.1f}", ci] + ["-"] * 6 + [verdict])
    return out


#: Requirement keys in the user's words, and their units.
_NAMES = {"em": ("Em", " lx"), "emin": ("Emin", " lx"), "u0": ("U0", ""), "ud": ("Ud", ""),
          "ugr": ("UGR", "")}


def requirement_lines(t: results_mod.TargetResult) -> List[Tuple[str, str]]:
    """("Em >= 500 lx", "pass") per requirement judged; an observer without a limit:
    ("UGR limit", "no limit set")."""
    if t.daylight_factor is not None:  # EN 17037's daylight factor verdicts
        return daylight_results.requirement_lines(t)
    out = []
    for key, verdict in t.verdicts.items():
        name, unit = _NAMES.get(key, (key, ""))
        if key == "ugr" and t.kind == "observer_grid":
            name = "max UGR"
        relation = "<=" if verdict.get("relation") == "<=" else ">="
        word = {"pass": "pass", "fail": "FAIL"}.get(t.verdict_of.get(key), "undecided")
        if t.estimated:
            word += " (est.)"
        out.append((f"{name} {relation} {float(verdict.get('required', 0.0)):g}{unit}", word))
    if t.is_glare and not t.verdicts:
        out.append(("UGR limit", NO_LIMIT))
    return out


def figure_lines(t: results_mod.TargetResult) -> List[Tuple[str, str, str]]:
    """(figure, value, interval) of a target, as its kind has them: an observer its UGR, a grid
    Em, Emin, Emax and U0, a face target Em."""
    if t.is_glare:
        name, interval = t.ugr_text()
        label, value = name.rsplit(" ", 1)
        low, high = t.ugr_ci
        if low is not None and high is not None:
            interval = _ci((low, high))  # the same "low - high" as the lux intervals
        elif low is None and high is None:
            interval = "-"
        return [(label, value, interval)]
    lines = [("Em", f"{t.mean_lux:.1f} lx", _ci((t.ci_low_lux, t.ci_high_lux)))]
    if t.daylight_factor is not None:  # the DF figures, then the daylight's lux
        lines = daylight_results.figure_lines(t.daylight_factor) + lines
    if t.kind == "grid":
        lines += [("Emin", f"{t.min_lux:.1f} lx", _ci(t.min_ci_lux)),
                  ("Emax", f"{t.max_lux:.1f} lx", _ci(t.max_ci_lux)),
                  ("U0", f"{t.uniformity:.2f}", _ci(t.uniformity_ci, 2))]
    return lines


def tooltip(t: results_mod.TargetResult, confidence: float) -> str:
    """A row's tooltip: the target and its kind, every figure with its interval, and each
    requirement with its verdict (an observer: UGR, interval, limit)."""
    level = f"{confidence * 100:g} %"
    lines = [f"{t.label} ({t.kind.replace('_', ' ')})"]
    for name, value, interval in figure_lines(t):
        lines.append(f"{name} {value}" + (f", {level} interval {interval}"
                                          if interval != "-" else ""))
    lines += [f"{rule}: {word}" for rule, word in requirement_lines(t)]
    return "\n".join(lines)


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


class NameAboveDelegate(QtGui.QStyledItemDelegate):
    """Paints each row of the results table as two parts: the target's name (column 0's text,
    bold) across the whole row, wrapped when longer than the row, and under it the cell's
    value. The model keeps one row per target with the name in column 0 (scripts and tests
    read it), but column 0 is hidden: a name beside three value columns got what they left
    over in the default combo view, a few pixels ("D... top")."""

    #: Pixels around the name inside its band.
    PAD = 4

    def __init__(self, table: QtGui.QTableWidget) -> None:
        super().__init__(table)
        self._table = table

    def name_font(self) -> QtGui.QFont:
        """The font of the names: the table's, bold (as the details table's titles)."""
        font = QtGui.QFont(self._table.font())
        font.setBold(True)
        return font

    def row_span(self) -> Tuple[int, int]:
        """(left, width) in viewport pixels of the row's visible columns."""
        table = self._table
        visible = [c for c in range(table.columnCount()) if not table.isColumnHidden(c)]
        if not visible:
            return 0, table.viewport().width()
        return table.columnViewportPosition(visible[0]), table.horizontalHeader().length()

    def name_rect(self, row: int, top: int = 0) -> QtCore.QRect:
        """Where row ``row``'s name is drawn (its band from ``top``): the row's width less the
        padding, as tall as the name wrapped to it."""
        left, width = self.row_span()
        inner = QtCore.QRect(left + self.PAD, top + self.PAD // 2,
                             max(width - 2 * self.PAD, 1), 100000)
        metrics = QtGui.QFontMetrics(self.name_font())
        text = self.name(row) or " "
        bound = metrics.boundingRect(inner, name_flags(metrics, text, inner.width()), text)
        return QtCore.QRect(inner.left(), inner.top(), inner.width(), bound.height())

    def name(self, row: int) -> str:
        """Row ``row``'s target name (column 0's text)."""
        item = self._table.item(row, 0)
        return item.text() if item is not None else ""

    def band_height(self, row: int) -> int:
        """The height of row ``row``'s name band (the name and its padding)."""
        return self.name_rect(row).height() + self.PAD

    def sizeHint(self, option: QtGui.QStyleOptionViewItem,
                 index: QtCore.QModelIndex) -> QtCore.QSize:
        size = super().sizeHint(option, index)
        return QtCore.QSize(size.width(),
                            size.height() + self.band_height(index.row()) + self.PAD // 2)

    def paint(self, painter: QtGui.QPainter, option: QtGui.QStyleOptionViewItem,
              index: QtCore.QModelIndex) -> None:
        band = self.band_height(index.row())
        cell = QtCore.QRect(option.rect)
        painter.save()
        # Each cell paints its own slice of the name: together the row shows it whole.
        painter.setClipRect(QtCore.QRect(cell.left(), cell.top(), cell.width(), band))
        painter.setFont(self.name_font())
        painter.setPen(option.palette.color(QtGui.QPalette.Text))
        rect = self.name_rect(index.row(), cell.top())
        text = self.name(index.row())
        painter.drawText(rect, name_flags(painter.fontMetrics(), text, rect.width()), text)
        painter.restore()
        value = QtGui.QStyleOptionViewItem(option)
        value.rect = QtCore.QRect(cell.left(), cell.top() + band, cell.width(),
                                  cell.height() - band - self.PAD // 2)  # clear of the rule
        super().paint(painter, value, index)
        painter.save()  # a rule under each target (the table draws no grid)
        painter.setPen(option.palette.color(QtGui.QPalette.Mid))
        painter.drawLine(cell.bottomLeft(), cell.bottomRight())
        painter.restore()


def name_flags(metrics: QtGui.QFontMetrics, text: str, width: int) -> int:
    """How a name is laid out in its band: left, top, wrapped between words; anywhere when a
    word is longer than the line ("Workplane_north_office"), which no word wrap can show."""
    longest = max((metrics.horizontalAdvance(w) for w in text.split()), default=0)
    wrap = QtCore.Qt.TextWrapAnywhere if longest > width else QtCore.Qt.TextWordWrap
    return int(QtCore.Qt.AlignLeft | QtCore.Qt.AlignTop | wrap)


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
        self.table.setWordWrap(True)  # only the verdict column is narrower than its text
        self.table.setVerticalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        self.table.setSelectionMode(QtGui.QAbstractItemView.NoSelection)
        self.table.setShowGrid(False)  # a vertical grid line would cut through the names
        self.names = NameAboveDelegate(self.table)
        self.table.setItemDelegate(self.names)
        self._fitted_width = -1
        self._refit_timer = QtCore.QTimer(self)  # a child: never fires after the panel closed
        self._refit_timer.setSingleShot(True)
        self._refit_timer.setInterval(0)
        self._refit_timer.timeout.connect(self._refit)
        # A wider or narrower panel wraps the names differently: fit the rows again.
        self.table.horizontalHeader().sectionResized.connect(self._width_changed)
        layout.addWidget(self.table)
        self.all_columns = QtGui.QCheckBox("All columns")
        self.all_columns.setToolTip("Show every figure with its confidence interval (Emin, "
                                    "Emax, U0; an observer's UGR and limit) and each "
                                    "requirement, one per line")
        self.all_columns.toggled.connect(self.layout_table)
        layout.addWidget(self.all_columns)
        # Every figure one per line: three narrow columns fit the default combo view, where
        # the eleven columns of the text table would need sideways scrolling.
        self.details = QtGui.QTableWidget(0, 3)
        self.details.setHorizontalHeaderLabels(["", "Value", "Interval"])
        self.details.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        self.details.verticalHeader().setVisible(False)
        self.details.setWordWrap(False)
        self.details.setTextElideMode(QtCore.Qt.ElideRight)
        self.details.setVerticalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        self.details.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        self.details.setSelectionMode(QtGui.QAbstractItemView.NoSelection)
        layout.addWidget(self.details)
        # EN 17037 sunlight exposure, a line per window (hidden without it).
        self.sunlight = QtGui.QLabel("")
        self.sunlight.setWordWrap(True)
        self.sunlight.setVisible(False)
        layout.addWidget(self.sunlight)
        self.facts = QtGui.QLabel("")
        self.facts.setWordWrap(True)
        layout.addWidget(self.facts)
        self.layout_table()

    def show_result(self, result: Optional[results_mod.AnalysisResult], facts: str) -> None:
        """Fill the table from ``result`` (empty: "No results yet") with ``facts`` under it."""
        self.table.setRowCount(0)
        lines = results_mod.sunlight_lines(result.sunlight) if result is not None else []
        self.sunlight.setText("\n".join(lines))
        self.sunlight.setVisible(bool(lines))
        # The value column's header names what its rows hold (lux, DF %, UGR).
        header = results_mod.value_header(result, grid_lux=False) if result else "Em lx"
        self.table.setHorizontalHeaderItem(COLUMNS.index("Em lx"),
                                           QtGui.QTableWidgetItem(header))
        if result is None:
            self.layout_table()
            self.facts.setText("No results yet: press Run.")
            return
        for row, (t, values) in enumerate(zip(result.targets, rows(result))):
            self.table.insertRow(row)
            tip = tooltip(t, result.confidence)
            for column, value in enumerate(values):
                item = QtGui.QTableWidgetItem(value)
                item.setToolTip(tip)
                colour = VERDICT_COLOURS.get(value.split(" ")[0]) \
                    if column == len(values) - 1 else None
                if colour is not None:
                    item.setForeground(QtGui.QBrush(QtGui.QColor(*colour)))
                self.table.setItem(row, column, item)
        self._fill_details(result)
        self.layout_table()
        self.facts.setText(facts)

    def _fill_details(self, result: Optional[results_mod.AnalysisResult]) -> None:
        """The details table: per target a title row, its figures (value, interval) and its
        requirements (rule, verdict)."""
        table = self.details
        table.setRowCount(0)
        bold = QtGui.QFont(table.font())
        bold.setBold(True)
        for t in result.targets if result is not None else []:
            tip = tooltip(t, result.confidence)
            row = table.rowCount()
            table.insertRow(row)
            title = QtGui.QTableWidgetItem(f"{t.label} ({t.kind.replace('_', ' ')})")
            title.setFont(bold)
            title.setToolTip(tip)
            table.setItem(row, 0, title)
            table.setSpan(row, 0, 1, 3)
            lines = [(n, v, i, None) for n, v, i in figure_lines(t)]
            lines += [(rule, "", word, VERDICT_COLOURS.get(word.split(" ")[0]))
                      for rule, word in requirement_lines(t)]
            for name, value, third, colour in lines:
                row = table.rowCount()
                table.insertRow(row)
                if not value:  # a requirement: its rule over two cells, the verdict
                    table.setSpan(row, 0, 1, 2)
                for column, text in enumerate((name, value, third)):
                    item = QtGui.QTableWidgetItem(text)
                    item.setToolTip(tip)
                    if column == 2 and colour is not None:
                        item.setForeground(QtGui.QBrush(QtGui.QColor(*colour)))
                    table.setItem(row, column, item)

    def layout_table(self, *args: Any) -> None:
        """The essential values (the names drawn above them, column 0 hidden), the Em column
        taking the spare width; with "All columns" the details table under it. Both as tall
        as their rows (the panel scrolls, not the tables) and never wider than the panel."""
        table = self.table
        header = table.horizontalHeader()
        for column, name in enumerate(COLUMNS):
            table.setColumnHidden(column, name not in ESSENTIAL_COLUMNS or column == 0)
            header.setSectionResizeMode(column, QtGui.QHeaderView.ResizeToContents)
        header.setSectionResizeMode(COLUMNS.index("Em lx"), QtGui.QHeaderView.Stretch)
        # The verdict column as wide as "undecided": a longer text ("no limit set",
        # "undecided (est.)") wraps onto a second line instead of widening the table.
        check = COLUMNS.index("Check")
        header.setSectionResizeMode(check, QtGui.QHeaderView.Fixed)
        metrics = QtGui.QFontMetrics(table.font())
        table.setColumnWidth(check, metrics.horizontalAdvance("undecided") + 12)
        table.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        _fit_height(table)
        self._fitted_width = header.length()
        details = self.details
        every = self.all_columns.isChecked()
        details.setVisible(every and details.rowCount() > 0)
        header = details.horizontalHeader()
        header.setSectionResizeMode(0, QtGui.QHeaderView.Stretch)
        for column in (1, 2):
            header.setSectionResizeMode(column, QtGui.QHeaderView.ResizeToContents)
        _fit_height(details)


    def _width_changed(self, *args: Any) -> None:
        """The columns were resized (the panel's width changed): once the resizing is over,
        fit the rows to the names as they now wrap."""
        self._refit_timer.start()

    def _refit(self) -> None:
        width = self.table.horizontalHeader().length()
        if width != self._fitted_width:  # only a new width: fitting changes heights only
            self._fitted_width = width
            _fit_height(self.table)


def _fit_height(table: QtGui.QTableWidget) -> None:
    """Make ``table`` exactly as tall as its header and rows."""
    header = table.horizontalHeader()
    table.resizeRowsToContents()
    height = header.height() + 2 * table.frameWidth()
    height += sum(table.rowHeight(r) for r in range(table.rowCount()))
    table.setFixedHeight(max(height, header.height() + 2 * table.frameWidth() + 4))
