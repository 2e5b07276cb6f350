# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of targets: plain when not computed, false colours with results."""
from __future__ import annotations

from typing import Any

from lighting.viewproviders.base import ViewProviderBase, set_if_exists

#: App properties whose change repaints the target (its colours come from its analysis'
#: results object, whose view provider repaints when they change).
REPAINT_ON = ("Shape",)


class ViewProviderTarget(ViewProviderBase):
    """Grid cells or target faces, coloured by illuminance."""

    ICON = "Lighting_Target"

    def __init__(self, vobj: Any) -> None:
        super().__init__(vobj)
        set_if_exists(vobj, "LineColor", (0.2, 0.2, 0.2))
        set_if_exists(vobj, "LineWidth", 1.0)
        set_if_exists(vobj, "Lighting", "Two side")

    def attach(self, vobj: Any) -> None:
        super().attach(vobj)
        if getattr(self, "light_model", None) is None:
            from pivy import coin

            # False colours are shown unshaded (BASE_COLOR) so they match the legend exactly.
            self.light_model = coin.SoLightModel()
            self.light_model.model = coin.SoLightModel.PHONG
            vobj.RootNode.insertChild(self.light_model, 0)

    def set_unlit(self, unlit: bool) -> None:
        """Unshaded colours (results) or normal shading (no results)."""
        model = getattr(self, "light_model", None)
        if model is not None:
            from pivy import coin

            model.model = coin.SoLightModel.BASE_COLOR if unlit else coin.SoLightModel.PHONG

    def getIcon(self) -> str:  # noqa: N802 (FreeCAD API name)
        from lighting.viewproviders.base import icon_path

        grid = getattr(getattr(self, "Object", None), "TargetType", "") == "Grid"
        return icon_path("Lighting_Grid" if grid else "Lighting_Target")

    def updateData(self, obj: Any, prop: str) -> None:  # noqa: N802
        if prop in REPAINT_ON:
            from lighting.viewproviders import coloring

            coloring.refresh_later(obj)
