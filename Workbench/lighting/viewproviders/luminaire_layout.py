# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of luminaire layouts: a yellow marker per member (the App object's shape),
the template luminaire as its child in the tree, the layout task panel to edit it."""
from __future__ import annotations

from typing import Any, List, Optional

import FreeCAD

from lighting.viewproviders.base import ViewProviderBase, set_if_exists


class ViewProviderLuminaireLayout(ViewProviderBase):
    """Members drawn like luminaires; double click opens the layout panel."""

    ICON = "Lighting_LuminaireLayout"

    def __init__(self, vobj: Any) -> None:
        super().__init__(vobj)
        set_if_exists(vobj, "ShapeColor", (1.0, 0.85, 0.1))
        set_if_exists(vobj, "LineColor", (0.9, 0.5, 0.0))
        set_if_exists(vobj, "LineWidth", 2.0)

    def claimChildren(self) -> List[Any]:  # noqa: N802 (FreeCAD API name)
        """The template (the layout's luminaire type) sits under the layout in the tree."""
        template = getattr(getattr(self, "Object", None), "Template", None)
        return [template] if template is not None else []

    def task_panel(self, vobj: Any) -> Optional[Any]:
        from lighting.taskpanels.layout_panel import LayoutTaskPanel

        return LayoutTaskPanel(layout=vobj.Object)

    def onDelete(self, vobj: Any, subelements: Any) -> bool:  # noqa: N802
        """Deleting a layout deletes its template too, unless something else uses it (else a
        hidden luminaire would stay behind and light the room on its own)."""
        obj = vobj.Object
        template = obj.Template
        from lighting.objects.base import proxy_type

        users = [o for o in (template.InList if template is not None else [])
                 if o != obj and proxy_type(o) != "Lighting::Analysis"]
        if template is not None and not users:
            # In the same transaction as the layout's deletion: one undo brings both back.
            obj.Template = None
            try:
                obj.Document.removeObject(template.Name)
            except Exception as exc:  # noqa: BLE001 - the user can still delete it by hand
                FreeCAD.Console.PrintWarning(f"Lighting: could not delete {template.Label}: "
                                             f"{exc}\n")
        return True
