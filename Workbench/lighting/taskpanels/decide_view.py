# SPDX-License-Identifier: LGPL-2.1-or-later
"""The analysis panel's "Undecided" section: per requirement still undecided (its interval
straddles the required value), what deciding it costs (the solver's ``to_decide`` forecast:
photons of a whole run and tracing seconds, docs/statistics.md "What deciding would cost") and
a *Decide* button that runs the analysis with Decide on and a photon budget from that forecast
(solver/decide.py: :data:`MARGIN` times it, since a run of exactly the forecast decides only
about half the time). A decide run goes on by itself to decide within the automatic limit
(``DecideLimitSeconds``); when deciding would take longer, the summary says so, with what it
needs, and the button does it. A run made with Decide off never tried: the summary says that,
not the limit, and offers the button and the Run settings' switch."""
from __future__ import annotations

from typing import Callable, List, NamedTuple, Optional

from PySide import QtGui

from lighting.solver import decide as decide_mod
from lighting.solver import machine
from lighting.solver import results as results_mod
from lighting.taskpanels.results_table import seconds_text

#: Budget of a Decide click over the forecast photons (solver/decide.py).
MARGIN = decide_mod.MARGIN
#: Names of the requirements in the user's words.
NAMES = {"em": "Em", "u0": "U0", "emin": "Emin", "ud": "Ud", "ugr": "UGR",
         "df_target": "DF over 50 %", "df_minimum": "DF over 95 %"}


class Undecided(NamedTuple):
    """One undecided requirement and what deciding it costs (photons None: never: the value
    sits on the bound)."""

    target: str
    name: str
    value: Optional[float]
    required: float
    relation: str
    photons: Optional[int]
    seconds: Optional[float]

    def text(self) -> str:
        """"Workplane Em 502.1 lx, required >= 500: about 1 234 000 photons (0.7 s)"."""
        unit = {"Em": " lx", "Emin": " lx"}.get(self.name, " %" if "DF" in self.name else "")
        digits = 2 if self.name in ("U0", "Ud") or "DF" in self.name else 1
        shown = "-" if self.value is None else f"{self.value:.{digits}f}{unit}"
        required = f"{self.required:.2f}" if "DF" in self.name else f"{self.required:g}"
        head = (f"{self.target} {self.name} {shown}, required {self.relation} "
                f"{required}{unit}")
        if self.photons is None:
            return head + ": the value sits on the requirement; no run can decide it"
        seconds = f", {seconds_text(self.seconds)}" if self.seconds is not None else ""
        return head + f": about {_count(self.photons)} photons{seconds} to decide"


def _count(photons: float) -> str:
    return f"{photons:,.0f}".replace(",", "\u202f")


def undecided(result: Optional[results_mod.AnalysisResult]) -> List[Undecided]:
    """Every undecided requirement of ``result`` with its ``to_decide`` forecast."""
    out: List[Undecided] = []
    for t in result.targets if result is not None else []:
        if t.estimated:  # point estimates are never undecided, and carry no forecast
            continue
        for key in t.undecided:
            verdict = t.verdicts[key]
            photons, seconds = t.to_decide.get(key, (None, None))
            out.append(Undecided(t.label, NAMES.get(key, key), verdict.get("value"),
                                 float(verdict.get("required", 0.0)),
                                 "<=" if verdict.get("relation") == "<=" else ">=",
                                 photons, seconds))
    return out


def budget(item: Undecided, traced: float) -> int:
    """The photon budget of a Decide click: MARGIN x the forecast (a run of the whole
    forecast decides about half the time), at least twice what was traced, rounded up to a
    thousand (solver/decide.py)."""
    return decide_mod.budget_for(float(item.photons or 0), traced)


def summary_text(result: results_mod.AnalysisResult,
                 limit_s: Optional[float] = None) -> str:
    """How many requirements are undecided, and why the run did not go on to decide them
    (Decide was off, the automatic limit ``limit_s``, default the preference, or a value on
    its bound) with what deciding needs."""
    text = (f"{len(undecided(result))} requirement(s) undecided after "
            f"{_count(result.photons)} photons: the interval still holds the required value.")
    off = decide_off_text(result)
    if off is not None:  # the run never tried: the automatic limit is not why
        return text + off
    plan = decide_mod.plan(result)
    limit = decide_mod.limit_seconds() if limit_s is None else limit_s
    if plan is not None and not plan.within(limit):
        text += f" The run did not decide them: {machine.why_not(plan, limit)}."
    text += " Decide traces until each is pass or FAIL (it stops as soon as they are)."
    return text


def decide_off_text(result: results_mod.AnalysisResult) -> Optional[str]:
    """What the summary says of a run made with *Decide requirements* off (the results'
    ``decide`` is false): it stopped where its settings said, without trying to decide, and
    how to decide; None for a decide run, or results that do not say."""
    if result.data.get("decide") is not False:
        return None
    how = {"accuracy": "at its accuracy goal", "time": "at its time limit"}.get(
        result.stop_reason, f"after its {_count(result.photons)} photons")
    text = (f" Decide requirements was off for this run, so it stopped {how} without trying "
            "to decide them.")
    if any(item.photons is not None for item in undecided(result)):
        text += (" Press Decide to trace until each is pass or FAIL (it stops as soon as they "
                 "are), or tick Decide requirements under Run settings for every run.")
    else:
        text += " A value sits exactly on its requirement, so no run can decide it."
    return text


class DecideView(QtGui.QWidget):
    """The rows of undecided requirements, each with its cost and a Decide button that calls
    ``decide(budget)``."""

    def __init__(self, decide: Callable[[int], None],
                 parent: Optional[QtGui.QWidget] = None) -> None:
        super().__init__(parent)
        self._decide = decide
        self.layout_ = QtGui.QVBoxLayout(self)
        self.layout_.setContentsMargins(0, 0, 0, 0)
        self.summary = QtGui.QLabel("")
        self.summary.setWordWrap(True)
        self.layout_.addWidget(self.summary)
        #: The Decide buttons shown, in row order (for tests and keyboard users).
        self.buttons: List[QtGui.QPushButton] = []
        self.items: List[Undecided] = []
        self._rows: List[QtGui.QWidget] = []

    def refresh(self, result: Optional[results_mod.AnalysisResult],
                running: bool = False) -> None:
        """Show the undecided requirements of ``result`` (the results the panel shows)."""
        for row in self._rows:
            self.layout_.removeWidget(row)
            row.deleteLater()
        self._rows, self.buttons = [], []
        self.items = undecided(result)
        if result is None:
            self.summary.setText("No results yet.")
        elif not self.items:
            self.summary.setText("Every requirement is decided (pass or FAIL from its "
                                 "interval)." if result.verdict else
                                 "No requirement was judged: set a target's required Em or "
                                 "an observer's UGR limit.")
        else:
            self.summary.setText(self.undecided_summary(result))
        for item in self.items:
            self._add_row(item, result, running)

    def undecided_summary(self, result: results_mod.AnalysisResult) -> str:
        """The summary over the rows (:func:`summary_text`)."""
        return summary_text(result)

    def set_running(self, running: bool) -> None:
        """No Decide while a run is in progress."""
        for button in self.buttons:
            button.setEnabled(not running)

    def _add_row(self, item: Undecided, result: results_mod.AnalysisResult,
                 running: bool) -> None:
        row = QtGui.QWidget()
        layout = QtGui.QVBoxLayout(row)
        layout.setContentsMargins(0, 2, 0, 2)
        label = QtGui.QLabel(item.text())
        label.setWordWrap(True)
        layout.addWidget(label)
        if item.photons is not None:
            photons = budget(item, result.photons)
            # Two lines: "Decide (2 154 000 photons at most)" on one is wider than the
            # default combo view and pushed the whole panel sideways.
            button = QtGui.QPushButton(f"Decide\n({_count(photons)} photons at most)")
            button.setToolTip(
                f"Run with Decide on and a budget of {_count(photons)} photons ({MARGIN} x the "
                "forecast, which decides only about half the time); the run stops at the first "
                "look where every requirement is decided")
            button.setEnabled(not running)
            button.clicked.connect(lambda checked=False, n=photons: self._decide(n))
            layout.addWidget(button)
            self.buttons.append(button)
        self.layout_.addWidget(row)
        self._rows.append(row)
