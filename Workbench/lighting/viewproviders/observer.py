# SPDX-License-Identifier: LGPL-2.1-or-later
"""GUI side of the Lighting objects: which view provider each object gets, and when.

App code never imports GUI code (Tests/workbench/test_app_imports.py checks it), so the App
factories and proxies do not attach view providers. A document observer, installed by
InitGui.py when the GUI starts, does:
- an object created in the GUI (a command, a script in the console) gets its view provider
  as soon as its Lighting proxy is set (synchronously: ``make_*`` returns it ready);
- a document being opened gets, once it is read, the view providers its file lacks (files
  saved by freecadcmd have no GuiDocument.xml) and ``restore.after_restore`` for the Arch
  objects and the visibility such files lose; results that older versions stored on the
  analysis and its targets move into a results object (solver/store.py ``migrate``).
Results colours come from the view providers' ``updateData`` (see coloring.py). Any change
of a document with a Lighting analysis (an edit, undo, redo, a deletion) also makes the
results state be computed again once the changes settle (results.py
``schedule_state_refresh``): a stale legend and panel follow an edited flux at once; and the
open Lighting panels show the document again (taskpanels/sync.py ``schedule``): after an Undo
the analysis panel's table is the document's, not the undone run's."""
from __future__ import annotations

import importlib
from typing import Any, Dict, Optional, Tuple

import FreeCAD

from lighting.objects.base import proxy_type

#: Lighting proxy type -> (module under lighting.viewproviders, class).
VIEW_PROVIDERS: Dict[str, Tuple[str, str]] = {
    "Lighting::Analysis": ("analysis", "ViewProviderAnalysis"),
    "Lighting::Luminaire": ("luminaire", "ViewProviderLuminaire"),
    "Lighting::Target": ("target", "ViewProviderTarget"),
    "Lighting::PlacementDomain": ("placement_domain", "ViewProviderPlacementDomain"),
    "Lighting::Results": ("results", "ViewProviderResults"),
    "Lighting::LuminaireLayout": ("luminaire_layout", "ViewProviderLuminaireLayout"),
    "Lighting::Observer": ("eye", "ViewProviderObserver"),
    "Lighting::LightScene": ("light_scene", "ViewProviderLightScene"),
    "Lighting::Sky": ("sky", "ViewProviderSky"),
    "Lighting::AnnualDaylight": ("annual", "ViewProviderAnnual"),
}

_observer: Optional["LightingObserver"] = None
_restoring: set = set()


def _has_python_view_provider(vobj: Any) -> bool:
    current = getattr(vobj, "Proxy", None)
    return current is not None and not isinstance(current, (int, float, str))  # missing: 0


def attach_view_provider(obj: Any) -> bool:
    """Give a Lighting object its view provider unless it has one; True if attached."""
    spec = VIEW_PROVIDERS.get(proxy_type(obj)) if obj is not None else None
    vobj = getattr(obj, "ViewObject", None) if spec is not None else None
    if vobj is None or _has_python_view_provider(vobj):
        return False
    module = importlib.import_module(f"lighting.viewproviders.{spec[0]}")
    proxy = getattr(module, spec[1])(vobj)
    if getattr(proxy, "ViewObject", None) is None:  # FreeCAD did not call attach()
        proxy.attach(vobj)
    return True


def finish_restore(doc_name: str) -> None:
    """After a document was read: missing view providers, then ``after_restore``."""
    _restoring.discard(doc_name)
    doc = FreeCAD.listDocuments().get(doc_name)
    if doc is None:
        return
    kinds = set()
    for obj in doc.Objects:
        kind = proxy_type(obj)
        if kind:
            kinds.add(kind)
            attach_view_provider(obj)
    if "Lighting::Analysis" in kinds:
        from lighting.objects.analysis import TYPE
        from lighting.objects.base import objects_of_type
        from lighting.solver.store import migrate
        from lighting.viewproviders.restore import after_restore

        for analysis in objects_of_type(doc, TYPE):
            if migrate(analysis):  # results stored the old way: now a results object
                for obj in doc.Objects:
                    attach_view_provider(obj)

        after_restore(doc)


class LightingObserver:
    """App document observer (FreeCAD.addDocumentObserver) living in the GUI."""

    def slotChangedObject(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API)
        _panels_may_change(obj)
        if prop not in STATE_NEUTRAL:
            _state_may_change(obj)
        if prop != "Proxy" or not proxy_type(obj):
            return
        try:
            doc = obj.Document
            if getattr(doc, "Restoring", False):
                # The file may bring its own view providers (GuiDocument.xml is read after
                # the objects): look once it is fully open.
                if doc.Name not in _restoring:
                    _restoring.add(doc.Name)
                    from PySide import QtCore

                    name = doc.Name
                    QtCore.QTimer.singleShot(0, lambda: finish_restore(name))
            else:
                attach_view_provider(obj)
        except Exception as exc:  # noqa: BLE001 - a view provider must never break the model
            FreeCAD.Console.PrintWarning(f"Lighting: no view provider for {obj.Name}: {exc}\n")


    def slotDeletedObject(self, obj: Any) -> None:  # noqa: N802 (FreeCAD API name)
        _panels_may_change(obj)
        _state_may_change(obj)

    def slotUndoDocument(self, doc: Any) -> None:  # noqa: N802 (FreeCAD API name)
        _panels_may_change(None, doc)
        _state_may_change(None, doc)

    def slotRedoDocument(self, doc: Any) -> None:  # noqa: N802 (FreeCAD API name)
        _panels_may_change(None, doc)
        _state_may_change(None, doc)


#: Property changes that never change a results state (viewing and naming).
STATE_NEUTRAL = ("Visibility", "Label", "Label2")


def _panels_may_change(obj: Any, doc: Any = None) -> None:
    """Schedule a refresh of the open Lighting panels (taskpanels/sync.py): what they show is
    the document's state, after any change, Undo and Redo included (debounced)."""
    try:
        doc = doc if doc is not None else obj.Document
        if doc is None or getattr(doc, "Restoring", False):
            return
        from lighting.taskpanels import sync

        sync.schedule(doc)
    except Exception:  # noqa: BLE001 - observers must never break the document
        pass


def _state_may_change(obj: Any, doc: Any = None) -> None:
    """Schedule a results-state refresh for the document (debounced; GUI documents with an
    analysis only)."""
    try:
        doc = doc if doc is not None else obj.Document
        if doc is None or getattr(doc, "Restoring", False) or doc.Name in _restoring:
            return
        from lighting.viewproviders.results import schedule_state_refresh

        schedule_state_refresh(doc)
    except Exception:  # noqa: BLE001 - observers must never break the document
        pass


def install() -> None:
    """Register the observer once (InitGui.py, at GUI start-up)."""
    global _observer
    if _observer is None:
        _observer = LightingObserver()
        FreeCAD.addDocumentObserver(_observer)
