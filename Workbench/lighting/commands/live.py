# SPDX-License-Identifier: LGPL-2.1-or-later
"""Live mode in the GUI: the *Live* toggle command and the analysis' ``Live`` property.

Setting ``Live`` (the command, the property editor or a script) starts a
:class:`lighting.solver.live.LiveSession` for the analysis; clearing it, closing the document
or deleting the analysis stops it. A Qt timer on the GUI thread polls the session: it hands
document changes over (debounced by the session) and shows the newest frame through the
results object (no undo step, solver/store.py ``write_live``); the view providers repaint from
it as after a run. The GUI thread never traces: the session's worker does."""
from __future__ import annotations

import math
from typing import Any, Dict, Optional, Tuple

import FreeCAD
import FreeCADGui

from lighting.commands.commands import BaseCommand, active_analysis

#: How often the GUI looks for a new frame (ms).
POLL_MS = 50

#: (document name, analysis name) -> its controller.
_controllers: Dict[Tuple[str, str], "LiveController"] = {}


def status_text(frame: Any) -> str:
    """The analysis' Status during a live session: photons, worst cell and open verdicts."""
    worst = frame.worst_cell_relative
    cell = f"worst cell +-{100.0 * worst:.1f} %" if math.isfinite(worst) else "cells still dark"
    photons = f"{frame.photons:,}".replace(",", " ")
    text = f"live: {photons} photons, {cell}"
    if frame.undecided:
        text += f", {frame.undecided} undecided"
    return text + (" (done)" if frame.finished else " (refining)")


class LiveController:
    """A live session of one analysis and the timer that shows its frames."""

    def __init__(self, analysis: Any) -> None:
        from PySide import QtCore

        from lighting.solver.live import LiveSession

        self.analysis = analysis
        self.frames_shown = 0
        #: (frame revision, session revision) of every frame shown: equal, or a stale frame
        self.shown_revisions: list = []
        self._reported: Optional[BaseException] = None
        self.session = LiveSession(analysis.Document, analysis)
        self.timer = QtCore.QTimer()
        self.timer.setInterval(POLL_MS)
        self.timer.timeout.connect(self.tick)
        self.timer.start()

    def tick(self) -> None:
        """Timer: hand changes over, show the newest frame (the only work on the GUI thread)."""
        from lighting.solver import store

        try:
            self.analysis.Name  # noqa: B018 - raises once the analysis is deleted
        except Exception:  # noqa: BLE001
            self.stop()
            return
        try:
            frame = self.session.take_frame()
        except Exception as exc:  # noqa: BLE001 - reported, live mode stays on, waiting
            FreeCAD.Console.PrintWarning(f"Lighting live: {exc}\n")
            return
        error = self.session.error
        if error is not None and error is not self._reported:
            self._reported = error  # once per error: the session waits for the next change
            FreeCAD.Console.PrintWarning(f"Lighting live: {str(error).splitlines()[0]}\n")
        if frame is None:
            return
        store.write_live(self.analysis, frame.data, self.session.fingerprint, status_text(frame))
        self.frames_shown += 1
        self.shown_revisions.append((frame.revision, self.session.revision))
        _update_panel(self.analysis)

    def stop(self) -> None:
        self.timer.stop()
        self.session.stop()


def _update_panel(analysis: Any) -> None:
    """The open analysis panel, if it shows this analysis, follows the frame."""
    from lighting.taskpanels import analysis_panel

    panel = analysis_panel.panel_of(analysis)
    if panel is not None:
        panel.show_live()


def controller(analysis: Any) -> Optional[LiveController]:
    """The running live controller of an analysis, if any."""
    return _controllers.get((analysis.Document.Name, analysis.Name))


def sync(analysis: Any) -> None:
    """Start or stop the live session to match the analysis' ``Live`` property."""
    key = (analysis.Document.Name, analysis.Name)
    running = _controllers.get(key)
    wanted = bool(getattr(analysis, "Live", False))
    if wanted and running is None:
        try:
            _controllers[key] = LiveController(analysis)
        except Exception as exc:  # noqa: BLE001 - e.g. the model does not export yet
            FreeCAD.Console.PrintError(f"Lighting live: {exc}\n")
            analysis.Live = False
    elif not wanted and running is not None:
        _controllers.pop(key).stop()
        from lighting.solver import store

        store.set_status(analysis, store.settled_status(analysis))


def stop_document(doc_name: str) -> None:
    """Stop every live session of a document (it is closing)."""
    for key in [k for k in _controllers if k[0] == doc_name]:
        _controllers.pop(key).stop()


class CommandLive(BaseCommand):
    NAME, ICON = "Lighting_Live", "Lighting_Live"
    MENU = "Live results"
    TIP = ("Refine the results in the background while you edit: luminaire and furniture "
           "moves update at once, other edits re-export (toggles the analysis' Live property)")

    def Activated(self) -> None:  # noqa: N802
        analysis = active_analysis(create=True)
        analysis.Live = not bool(analysis.Live)
        FreeCADGui.updateGui()


ALL = (CommandLive,)
