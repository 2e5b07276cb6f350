# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of luminaires: a yellow symbol with its aim line."""
from __future__ import annotations

from typing import Any

from lighting.viewproviders.base import ViewProviderBase, set_if_exists


class ViewProviderLuminaire(ViewProviderBase):
    """Luminaire symbol (sphere, cone or panel) in warm yellow."""

    ICON = "Lighting_Luminaire"
    MODELESS = True

    def __init__(self, vobj: Any) -> None:
        super().__init__(vobj)
        set_if_exists(vobj, "ShapeColor", (1.0, 0.85, 0.1))
        set_if_exists(vobj, "LineColor", (0.9, 0.5, 0.0))
        set_if_exists(vobj, "LineWidth", 2.0)

    def task_panel(self, vobj: Any) -> Any:
        """Double-click / Edit: the luminaire chooser, with this luminaire selected."""
        from lighting.taskpanels.luminaire_chooser import LuminaireChooserPanel

        return LuminaireChooserPanel(vobj.Object)

    def setupContextMenu(self, vobj: Any, menu: Any) -> None:  # noqa: N802 (FreeCAD API name)
        """Context menu entry "Choose luminaire data..." (the same chooser)."""
        action = menu.addAction("Choose luminaire data...")
        action.triggered.connect(lambda: vobj.Document.setEdit(vobj.Object.Name))
