# SPDX-License-Identifier: LGPL-2.1-or-later
"""Optimize placement's own *Decide*: the chosen layout applied (when it is not yet) and the
analysis run with Decide on until every requirement of the document is pass or FAIL.

The optimizer ranks layouts on its own screening and confirmation traces: a layout at 502 lx
against 500 lx is "feasible" there, while the analysis' default run leaves it undecided. One
click traces the chosen layout as the analysis does, with Decide on; the run goes on by itself
within the automatic limit (solver/decide.py, ``DecideLimitSeconds``). Where deciding needs
more, the panel says what (photons, seconds) and why the run stopped, and the next click
traces that budget. The run stores its results in the document like any run (one undo step),
so the analysis panel, the 3D colours and the legend show them too."""
from __future__ import annotations

from typing import Any, List, Optional

import FreeCAD
from PySide import QtCore, QtGui

from lighting.messages import LightingError
from lighting.solver import decide as decide_mod
from lighting.solver import machine, store
from lighting.solver import results as results_mod
from lighting.taskpanels.decide_view import NAMES
from lighting.taskpanels.results_table import seconds_text

POLL_MS = 100


def verdict_lines(result: results_mod.AnalysisResult) -> List[str]:
    """"Workplane: Em 502.3 lx >= 500 lx pass, U0 0.63 >= 0.60 undecided" per judged target."""
    lines = []
    for t in result.targets:
        parts = []
        for key, verdict in t.verdicts.items():
            name = NAMES.get(key, key)
            unit = " lx" if key in ("em", "emin") else ""
            digits = 2 if key in ("u0", "ud") else 1
            value = verdict.get("value")
            shown = "-" if value is None else f"{value:.{digits}f}{unit}"
            relation = "<=" if verdict.get("relation") == "<=" else ">="
            word = {"pass": "pass", "fail": "FAIL"}.get(t.verdict_of.get(key), "undecided")
            parts.append(f"{name} {shown} {relation} {float(verdict.get('required', 0)):g}"
                         f"{unit} {word}")
        if parts:
            lines.append(f"{t.label}: {', '.join(parts)}")
    return lines


def luminaires_now(analysis: Any) -> List[Any]:
    """(name, position in mm rounded to 0.1 mm) of the analysis' luminaires, sorted."""
    from lighting.objects import analysis as analysis_mod

    out = []
    for obj in analysis_mod.luminaires(analysis):
        base = obj.getGlobalPlacement().Base
        out.append((obj.Name, round(base.x, 1), round(base.y, 1), round(base.z, 1)))
    return sorted(out)


class OptimizeDecide:
    """The Decide button and its run for an Optimize placement panel (``panel``: its
    ``analysis``, ``result``, ``selected_member()``, ``apply()``, ``set_busy()``)."""

    TIP = ("Apply the selected layout (if it is not applied) and run the analysis with Decide "
           "on until its requirements are pass or FAIL, going on by itself within the "
           "automatic limit (the results are stored like a run's)")

    def __init__(self, panel: Any) -> None:
        self.panel = panel
        self.job: Optional[machine.AnalysisRun] = None
        #: The budget of the next click when the last run stopped at the limit (else None:
        #: the analysis' Photons, going on by itself within the limit).
        self.budget: Optional[int] = None
        self.applied: Optional[int] = None
        #: The analysis' luminaires right after Apply (luminaires_now): Decide traces the
        #: applied layout only while the document still holds it.
        self.snapshot: List[Any] = []
        self._budgeted = False
        self.button = QtGui.QPushButton("Decide")
        self.button.setToolTip(self.TIP)
        self.button.setMinimumWidth(40)
        self.button.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Fixed)
        self.button.setEnabled(False)
        self.button.clicked.connect(self.start)
        self.label = QtGui.QLabel("")
        self.label.setWordWrap(True)
        self.label.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Preferred)
        self.label.setTextInteractionFlags(QtCore.Qt.TextSelectableByMouse)
        self.timer = QtCore.QTimer()
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self._poll)

    def is_busy(self) -> bool:
        """True while the Decide run is in progress."""
        return self.job is not None and not self.job.finished

    def enable(self, on: bool) -> None:
        """Decide is possible when there is a layout to trace and nothing runs."""
        self.button.setEnabled(on and not self.is_busy())

    def was_applied(self, member: int) -> None:
        """Layout ``member`` was just applied: remember what the document holds now; another
        layout than before starts from the analysis' own budget again."""
        if self.applied != member:
            self.budget = None
        self.applied = member
        self.snapshot = luminaires_now(self.panel.analysis)

    def forget(self) -> None:
        """A new search: the next Decide starts from the analysis' own budget again."""
        self.budget, self.applied, self.snapshot = None, None, []
        self.button.setToolTip(self.TIP)
        self.label.setText("")

    def start(self) -> None:
        """Apply the chosen layout if needed, then run with Decide on (worker thread)."""
        panel = self.panel
        if self.is_busy() or panel.is_busy() or panel.result is None:
            return
        member = panel.selected_member()
        if self.applied != member:
            panel.apply()  # sets applied and the snapshot
        elif self.snapshot != luminaires_now(panel.analysis):
            self.label.setText(f"The document no longer holds layout {member + 1} as applied "
                               "(an Undo or an edit since): Apply it again, then Decide.")
            return
        analysis = panel.analysis
        photons = self.budget or int(analysis.Photons)
        store.write_settings(analysis, Photons=photons, TargetAccuracy=0.0, Decide=True)
        # A second click traces the budget it was told; the first goes on within the limit.
        self._budgeted = bool(self.budget)
        limit = 0.0 if self._budgeted else None
        self.job = machine.AnalysisRun(analysis, log=self._log, spare_core=True,
                                       decide_limit_s=limit)
        try:
            self.job.check()
            self.job.prepare()
            self.job.start()
        except LightingError as exc:
            self.label.setText(f"Decide failed: {self.job.fail(exc).splitlines()[0]}")
            self.job = None
            return
        self.label.setText(f"Deciding layout {member + 1}: tracing at most "
                           f"{decide_mod.photons_text(photons)} photons...")
        panel.set_busy(True)
        self.timer.start()

    def cancel(self) -> None:
        """Stop the Decide run (its partial results are kept, marked partial)."""
        if self.is_busy():
            self.job.cancel()

    def _log(self, level: str, text: str) -> None:
        line = f"Optimize placement: {text}\n"
        if level == "error":
            FreeCAD.Console.PrintError(line)
        elif level == "warning":
            FreeCAD.Console.PrintWarning(line)
        else:
            FreeCAD.Console.PrintMessage(line)

    def _poll(self) -> None:
        job = self.job
        if job is None:
            self.timer.stop()
            return
        if not job.finished:
            if job.total > 0:
                self.label.setText(f"Deciding: {job.done:,} / {job.total:,} photons")
            return
        self.timer.stop()
        self.panel.set_busy(False)
        if job.error is not None:
            self.label.setText(f"Decide: {job.fail(job.error).splitlines()[0]}")
            return
        try:
            result = job.apply()
        except Exception as exc:  # noqa: BLE001 - e.g. the document was closed
            self.label.setText(f"Decide failed: {job.fail(exc)}")
            return
        self.show(result, job)

    def show(self, result: results_mod.AnalysisResult, job: machine.AnalysisRun) -> None:
        """The verdicts of the traced layout and, while some stay undecided, why and what
        deciding needs (the next click traces it)."""
        traced = max(job.photons_traced, int(result.photons))
        head = (f"Layout {(self.applied or 0) + 1} traced: {decide_mod.photons_text(traced)} "
                f"photons in {seconds_text(job.wall_seconds())}")
        if job.continued:
            head += " (went on by itself to decide)"
        lines = [head + "."] + verdict_lines(result)
        plan = decide_mod.plan(result)
        if plan is None:
            self.budget = None
            self.button.setToolTip(self.TIP)
            lines.append("Every requirement decided." if result.verdict else
                         "No requirement was judged: set the target's required Em.")
        else:
            if self._budgeted and plan.budget:  # the told budget was not enough this time
                why = (f"still undecided after that budget; deciding needs up to "
                       f"{decide_mod.photons_text(plan.budget)} photons: press Decide")
            else:
                why = machine.why_not(plan, decide_mod.limit_seconds())
            lines.append(f"Undecided: {why}.")
            self.budget = plan.budget or None
            about = "" if plan.seconds is None else f" (about {seconds_text(plan.seconds)})"
            self.button.setToolTip(
                f"Trace layout {(self.applied or 0) + 1} again with Decide on and at most "
                f"{decide_mod.photons_text(plan.budget)} photons{about}; the run stops as soon "
                "as every requirement is decided" if plan.budget else self.TIP)
        self.label.setText("\n".join(lines))
        FreeCAD.Console.PrintMessage("Optimize placement: " + " ".join(lines) + "\n")
        QtCore.QTimer.singleShot(0, self._scroll_to_label)

    def _scroll_to_label(self) -> None:
        """Bring the outcome into view: the task view scrolls the whole panel."""
        parent = self.label.parentWidget()
        while parent is not None and not isinstance(parent, QtGui.QScrollArea):
            parent = parent.parentWidget()
        if parent is not None:
            parent.ensureWidgetVisible(self.label)
