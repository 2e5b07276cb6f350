# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of light scenes: double-click shows the scene (the analysis' results are
rescaled to its levels, no tracing) and opens the analysis panel, where its levels are edited."""
from __future__ import annotations

from typing import Any, Optional

from lighting.viewproviders.base import ViewProviderBase


class ViewProviderLightScene(ViewProviderBase):
    """A light scene in the tree."""

    ICON = "Lighting_LightScene"
    MODELESS = True

    def task_panel(self, vobj: Any) -> Optional[Any]:
        from lighting.objects import light_scene
        from lighting.taskpanels.analysis_panel import AnalysisTaskPanel

        analysis = light_scene.analysis_of(vobj.Object)
        if analysis is None:
            return None
        if light_scene.active(analysis) is not vobj.Object:
            analysis.ActiveLightScene = vobj.Object
        return AnalysisTaskPanel(analysis)
