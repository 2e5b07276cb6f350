# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of the annual daylight analysis: repaints its analysis' grids when its
results or its Map change; double-click opens its panel (taskpanels/annual_panel.py)."""
from __future__ import annotations

from typing import Any, Optional

from lighting.viewproviders.base import ViewProviderBase

#: App properties whose change repaints the grids.
REPAINT_ON = ("SummaryJson", "Map")


class ViewProviderAnnual(ViewProviderBase):
    """A year of daylight in the tree."""

    ICON = "Lighting_AnnualDaylight"
    MODELESS = True

    def updateData(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        if prop in REPAINT_ON and not getattr(obj.Document, "Restoring", False):
            from lighting.objects import annual as annual_mod
            from lighting.viewproviders import coloring

            owner = annual_mod.analysis_of(obj)
            if owner is not None:
                coloring.refresh_later(owner)

    def task_panel(self, vobj: Any) -> Optional[Any]:
        from lighting.taskpanels.annual_panel import AnnualPanel

        return AnnualPanel(vobj.Object)
