# SPDX-License-Identifier: LGPL-2.1-or-later
"""What every Lighting task panel shares: it shows the document's state, it coexists with the
commands, and the mouse wheel scrolls it instead of changing its fields.

- **One source of truth.** Panels are opened through :func:`show`, which registers them. The
  GUI's document observer (viewproviders/observer.py) calls :func:`schedule` on any change of a
  document (an edit, a deletion, Undo, Redo); once the burst of changes settles every open
  panel's ``refresh()`` shows the document again (the analysis panel: its table, legend,
  verdicts, settings). The command that made the change does not need to know the panel.
  A panel whose analysis was deleted (or its creation undone) closes itself.
- **Coexistence.** :func:`close_current` closes the open Lighting panel before another opens,
  or says why it cannot (a run or a search in progress), instead of failing on a panel whose
  widgets FreeCAD already deleted (it sets a closed dialog's ``form`` to None).
- **Wheel guard.** Spin boxes and combo boxes take focus only by click or Tab, and a wheel
  event over one that has no focus goes on to the scroll area (:func:`guard_wheel`)."""
from __future__ import annotations

from typing import Any, List, Optional

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

#: Wait this long after the last document change before the panels show the document again.
REFRESH_DELAY_MS = 150

_panels: List[Any] = []
_scheduled: set = set()


# -- registry --------------------------------------------------------------------------
def is_shown(panel: Any) -> bool:
    """True while ``panel``'s widgets are in the task view (False once FreeCAD closed it:
    it deletes the widgets and sets ``form`` to None)."""
    form = getattr(panel, "form", None) if panel is not None else None
    if form is None or not FreeCADGui.Control.activeDialog():
        return False
    try:
        return form.parentWidget() is not None
    except RuntimeError:  # the C++ widget is gone
        return False


def open_panels() -> List[Any]:
    """The Lighting panels shown now (normally one: the task view holds one dialog)."""
    _panels[:] = [p for p in _panels if is_shown(p)]
    return list(_panels)


def register(panel: Any) -> Any:
    """Track ``panel`` for refreshes and guard its fields against the wheel."""
    guard_wheel(panel.form)
    if panel not in _panels:
        _panels.append(panel)
    return panel


def show(panel: Any) -> Any:
    """Open ``panel`` in the task view (after :func:`close_current`); returns it."""
    register(panel)
    FreeCADGui.Control.showDialog(panel)
    return panel


def is_busy(panel: Any) -> bool:
    """Whether the panel is running something that closing it would cancel."""
    check = getattr(panel, "is_busy", None)
    try:
        return bool(check()) if callable(check) else False
    except Exception:  # noqa: BLE001 - a broken panel does not block the others
        return False


def tell(text: str) -> None:
    """A message the user sees (status bar) and can read again (report view)."""
    FreeCAD.Console.PrintWarning(f"Lighting: {text}\n")
    FreeCADGui.getMainWindow().statusBar().showMessage(f"Lighting: {text}", 10000)


def close_current() -> bool:
    """Close the open task dialog so that another panel can open. False (and the user told
    why) when a Lighting panel is running a solve or a search."""
    for panel in open_panels():
        if is_busy(panel):
            title = panel.form.windowTitle() or "a Lighting panel"
            tell(f"'{title}' is running: wait for it or press its Cancel first")
            FreeCADGui.Control.showTaskView()
            return False
    for panel in open_panels():
        panel.reject()  # stops its timers and threads, closes the dialog, leaves edit mode
    if FreeCADGui.Control.activeDialog():
        FreeCADGui.Control.closeDialog()
    return True


# -- refresh on document changes -------------------------------------------------------
def schedule(doc: Any) -> None:
    """Refresh the open panels once the document's current burst of changes is over."""
    if not _panels:
        return
    name = doc.Name
    if name in _scheduled:
        return
    _scheduled.add(name)
    QtCore.QTimer.singleShot(REFRESH_DELAY_MS, lambda: refresh_document(name))


def _document_of(panel: Any) -> Optional[str]:
    for attr in ("analysis", "layout", "luminaire"):
        obj = getattr(panel, attr, None)
        if obj is not None:
            try:
                return obj.Document.Name
            except Exception:  # noqa: BLE001 - deleted: judged by refresh_panel
                return None
    return None


def object_alive(obj: Any) -> bool:
    """Whether ``obj`` is still in its document (not deleted, its creation not undone)."""
    try:
        doc = obj.Document
        return doc is not None and doc.getObject(obj.Name) is not None
    except Exception:  # noqa: BLE001 - the object's C++ side is gone
        return False


def refresh_document(doc_name: str) -> None:
    """Show the document's state in every open Lighting panel of ``doc_name``."""
    _scheduled.discard(doc_name)
    for panel in open_panels():
        if _document_of(panel) in (doc_name, None):
            refresh_panel(panel)


def refresh_panel(panel: Any) -> None:
    """``panel.refresh()``; a panel whose analysis is gone is closed with a message."""
    analysis = getattr(panel, "analysis", None)
    if analysis is not None and not object_alive(analysis):
        if is_busy(panel):
            panel.cancel()
        panel.reject()
        tell("the panel's analysis was deleted: the panel was closed")
        return
    refresh = getattr(panel, "refresh", None)
    if not callable(refresh):
        return
    try:
        refresh()
        guard_wheel(panel.form)  # fields a refresh added (light scene levels)
    except Exception as exc:  # noqa: BLE001 - a refresh must never break the document
        FreeCAD.Console.PrintWarning(f"Lighting: cannot refresh the panel: {exc}\n")


# -- wheel guard -----------------------------------------------------------------------
#: Fields that the wheel changes in Qt's default behaviour.
WHEEL_FIELDS = (QtGui.QAbstractSpinBox, QtGui.QComboBox)


class WheelGuard(QtCore.QObject):
    """Event filter: a wheel over an unfocused field scrolls the panel instead; fields added
    later under a guarded widget are guarded when Qt polishes them."""

    def eventFilter(self, watched: Any, event: Any) -> bool:  # noqa: N802 (Qt API name)
        kind = event.type()
        if kind == QtCore.QEvent.Wheel and isinstance(watched, WHEEL_FIELDS) \
                and not watched.hasFocus():
            event.ignore()  # ignored: Qt passes it on to the parents (the scroll area)
            return True
        if kind == QtCore.QEvent.ChildPolished:
            child = event.child()
            if isinstance(child, QtGui.QWidget):
                _guard_one(child)
        return False


_guard: Optional[WheelGuard] = None


def _guard_one(widget: Any) -> None:
    try:
        if widget.property("lightingWheelGuard"):
            return
        widget.setProperty("lightingWheelGuard", True)
        if isinstance(widget, WHEEL_FIELDS):
            widget.setFocusPolicy(QtCore.Qt.StrongFocus)  # no focus from the wheel
        widget.installEventFilter(_guard)
    except RuntimeError:
        # Its C++ object is already deleted (a panel closing while the document changes, e.g.
        # a Delete: the task dialog's button box goes first): nothing left to guard.
        return


def guard_wheel(root: Any) -> None:
    """Guard ``root`` and every widget under it (idempotent)."""
    global _guard
    if root is None:
        return
    if _guard is None:
        _guard = WheelGuard()
    _guard_one(root)
    for widget in root.findChildren(QtGui.QWidget):
        _guard_one(widget)
