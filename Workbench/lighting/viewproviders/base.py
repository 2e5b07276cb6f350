# SPDX-License-Identifier: LGPL-2.1-or-later
"""Base view provider (GUI only): icons by object role, edit mode with a task panel."""
from __future__ import annotations

import os
from typing import Any, Optional

import FreeCAD
import FreeCADGui

ICON_DIR = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))), "Resources", "icons")


def icon_path(name: str) -> str:
    """Absolute path of ``Resources/icons/<name>.svg``."""
    return os.path.join(ICON_DIR, f"{name}.svg")


class ViewProviderBase:
    """Common behaviour; subclasses set ICON and may open a task panel in ``setEdit``."""

    ICON = "Lighting_Workbench"

    def __init__(self, vobj: Any) -> None:
        vobj.Proxy = self
        self.Object = vobj.Object

    def attach(self, vobj: Any) -> None:
        """Called on creation and when a document is restored."""
        self.Object = vobj.Object
        self.ViewObject = vobj

    def getIcon(self) -> str:  # noqa: N802 (FreeCAD API name)
        return icon_path(self.ICON)

    def task_panel(self, vobj: Any) -> Optional[Any]:
        """The task panel to edit the object, or None for the property editor only."""
        return None

    #: True when ``task_panel`` is modeless (taskpanels/modeless.py): it opens without edit
    #: mode, because FreeCAD hands Edit > Delete of an object in edit mode to that object's
    #: sub-elements (nothing is deleted) and the panel works on the model as it is anyway.
    MODELESS = False

    def setEdit(self, vobj: Any, mode: int = 0) -> bool:  # noqa: N802
        if mode != 0:
            return False
        if self.MODELESS:  # the context menu's Edit: the panel, outside edit mode
            from PySide import QtCore

            QtCore.QTimer.singleShot(0, lambda: self.open_panel(vobj))
            return False
        panel = self.task_panel(vobj)
        if panel is None:
            return False
        from lighting.taskpanels import sync

        FreeCADGui.Control.closeDialog()
        sync.show(panel)
        return True

    def unsetEdit(self, vobj: Any, mode: int = 0) -> bool:  # noqa: N802
        FreeCADGui.Control.closeDialog()
        return True

    def open_panel(self, vobj: Any) -> Optional[Any]:
        """Open the object's modeless panel (after closing the open one, unless that one is
        busy: the user is told why); returns it or None."""
        from lighting.taskpanels import sync

        try:
            if not sync.close_current():
                return None
            panel = self.task_panel(vobj)
        except Exception as exc:  # noqa: BLE001 - e.g. the object was deleted meanwhile
            FreeCAD.Console.PrintWarning(f"Lighting: cannot open the panel: {exc}\n")
            return None
        return sync.show(panel) if panel is not None else None

    def doubleClicked(self, vobj: Any) -> bool:  # noqa: N802
        # Asks whether the class has a panel without building one: a panel built only to be
        # dropped would be collected later, at any moment, taking its Qt widgets along.
        if type(self).task_panel is ViewProviderBase.task_panel:
            return False
        if self.MODELESS:
            self.open_panel(vobj)
            return True
        from lighting.taskpanels import sync

        if sync.close_current():
            vobj.Document.setEdit(vobj.Object.Name)
        return True

    # No state: the view provider is rebuilt from the document.
    def __getstate__(self) -> None:
        return None

    def __setstate__(self, state: Any) -> None:
        return None

    def dumps(self) -> None:
        return None

    def loads(self, state: Any) -> None:
        return None


def set_if_exists(vobj: Any, name: str, value: Any) -> None:
    """Set a view property when this FreeCAD version has it."""
    if name in vobj.PropertiesList:
        try:
            setattr(vobj, name, value)
        except Exception as exc:  # noqa: BLE001 - cosmetic only
            FreeCAD.Console.PrintLog(f"Lighting: cannot set {name}: {exc}\n")
