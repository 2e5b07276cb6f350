# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of the results object: repaints its analysis' targets and legend when the
results change (stored, updated, undone); double-click opens the analysis' task panel."""
from __future__ import annotations

from typing import Any, Optional

from lighting.viewproviders.base import ViewProviderBase

#: App properties of the results object whose change repaints.
REPAINT_ON = ("ResultsJson",)


class ViewProviderResults(ViewProviderBase):
    """Results of one analysis run, shown as false colours on the analysis' targets."""

    ICON = "Lighting_Results"

    def updateData(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        if prop in REPAINT_ON:
            from lighting.viewproviders import coloring

            coloring.refresh_later(obj)

    def task_panel(self, vobj: Any) -> Optional[Any]:
        from lighting.objects.results import analysis_of
        from lighting.taskpanels.analysis_panel import AnalysisTaskPanel

        analysis = analysis_of(vobj.Object)
        return AnalysisTaskPanel(analysis) if analysis is not None else None
