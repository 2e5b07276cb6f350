# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of the Sky: its portals drawn in translucent sky blue."""
from __future__ import annotations

from typing import Any

from lighting.viewproviders.base import ViewProviderBase, set_if_exists


class ViewProviderSky(ViewProviderBase):
    """The portals (parallelograms with an arrow into the room); edited in the property
    editor, summarised in its panel."""

    ICON = "Lighting_Sky"
    MODELESS = True

    def __init__(self, vobj: Any) -> None:
        super().__init__(vobj)
        set_if_exists(vobj, "ShapeColor", (0.55, 0.8, 1.0))
        set_if_exists(vobj, "LineColor", (0.1, 0.3, 0.8))
        set_if_exists(vobj, "LineWidth", 3.0)
        set_if_exists(vobj, "Transparency", 50)

    def task_panel(self, vobj: Any) -> Any:
        """Double-click: the Sky's summary panel (what it exports, the glazing defaults)."""
        from lighting.taskpanels.sky_panel import SkyPanel

        return SkyPanel(vobj.Object)
