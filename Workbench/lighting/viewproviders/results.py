# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of the results object: repaints its analysis' targets and legend when the
results change (stored, updated, undone); double-click opens the analysis' task panel.

It also keeps the GUI's picture of the results *state* true: the App side computes whether
results are stale (solver/store.py ``results_state``, a fingerprint comparison, no export);
the GUI observer (observer.py) calls :func:`schedule_state_refresh` after any change of a
document, and once the burst of changes is over the state is computed again, and the legend
(greyed, "out of date") and the open analysis panel follow when it changed."""
from __future__ import annotations

from typing import Any, Dict, Optional, Tuple

import FreeCAD

from lighting.viewproviders.base import ViewProviderBase

#: App properties of the results object whose change repaints.
REPAINT_ON = ("ResultsJson", "InputsFingerprint", "LightScene")
#: Wait this long after the last change before computing the state again.
STATE_DELAY_MS = 250

#: (document, analysis) -> the last state computed for it (solver/store.py ResultsState).
_known: Dict[Tuple[str, str], Any] = {}
_scheduled: set = set()


class ViewProviderResults(ViewProviderBase):
    """Results of one analysis run, shown as false colours on the analysis' targets."""

    ICON = "Lighting_Results"
    MODELESS = True

    def updateData(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        if prop in REPAINT_ON:
            from lighting.objects.results import analysis_of
            from lighting.viewproviders import coloring

            owner = analysis_of(obj)
            if owner is not None:
                _known.pop((obj.Document.Name, owner.Name), None)
            coloring.refresh_later(obj)

    def task_panel(self, vobj: Any) -> Optional[Any]:
        from lighting.objects.results import analysis_of
        from lighting.taskpanels.analysis_panel import AnalysisTaskPanel

        analysis = analysis_of(vobj.Object)
        return AnalysisTaskPanel(analysis) if analysis is not None else None


def current_state(analysis: Any) -> Any:
    """The analysis' results state, computed once per change burst."""
    key = (analysis.Document.Name, analysis.Name)
    found = _known.get(key)
    if found is None:
        from lighting.solver.store import results_state

        found = _known[key] = results_state(analysis)
    return found


def schedule_state_refresh(doc: Any) -> None:
    """Compute the states of the document's analyses again once its changes settle."""
    name = doc.Name
    if name in _scheduled:
        return
    _scheduled.add(name)
    from PySide import QtCore

    QtCore.QTimer.singleShot(STATE_DELAY_MS, lambda: refresh_state(name))


def refresh_state(doc_name: str) -> None:
    """Recompute each analysis' results state; repaint its legend and update the open panel
    when the state changed."""
    _scheduled.discard(doc_name)
    doc = FreeCAD.listDocuments().get(doc_name)
    if doc is None:
        return
    from lighting.objects.analysis import TYPE
    from lighting.objects.base import objects_of_type
    from lighting.objects.results import of_analysis
    from lighting.solver.store import results_state
    from lighting.viewproviders import coloring

    for analysis in objects_of_type(doc, TYPE):
        key = (doc_name, analysis.Name)
        if of_analysis(analysis) is None and key not in _known:
            continue
        try:
            state = results_state(analysis)
        except Exception as exc:  # noqa: BLE001 - a state display must never break editing
            FreeCAD.Console.PrintLog(f"Lighting: results state of {analysis.Name}: {exc}\n")
            continue
        old = _known.get(key)
        _known[key] = state
        if old is None or (old.state, old.changes) != (state.state, state.changes):
            coloring.refresh(analysis)
            _show_in_panel(analysis, state)


def _show_in_panel(analysis: Any, state: Any) -> None:
    from lighting.taskpanels import analysis_panel

    panel = analysis_panel.panel_of(analysis)
    if panel is not None:
        panel.show_state(state)
