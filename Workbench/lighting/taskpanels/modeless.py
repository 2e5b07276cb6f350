# SPDX-License-Identifier: LGPL-2.1-or-later
"""The task dialogs that leave the model editable while they are open.

FreeCAD disables every command that alters the document, the view or the selection while a
task dialog that does not allow it is open, so with a plain panel open the Lighting toolbars
are greyed out. Panels that work on the model as it is (analysis, optimizer, luminaire
chooser) derive from ``ModelessPanel``; editors with their own transaction and Cancel
(the layout panel) stay modal."""
from __future__ import annotations


class ModelessPanel:
    """Task dialog mixin: the model, the view and the selection stay editable."""

    def isAllowedAlterDocument(self) -> bool:  # noqa: N802 (FreeCAD API name)
        return True

    def isAllowedAlterView(self) -> bool:  # noqa: N802 (FreeCAD API name)
        return True

    def isAllowedAlterSelection(self) -> bool:  # noqa: N802 (FreeCAD API name)
        return True

    def close_dialog(self) -> None:
        """Close the task dialog and leave edit mode (a panel opened by double-click)."""
        import FreeCADGui

        FreeCADGui.Control.closeDialog()
        try:
            FreeCADGui.ActiveDocument.resetEdit()
        except Exception:  # noqa: BLE001 - not in edit mode
            pass
