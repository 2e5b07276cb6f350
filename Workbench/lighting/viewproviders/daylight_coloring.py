# SPDX-License-Identifier: LGPL-2.1-or-later
"""Paint daylight-factor grids (GUI only): their cells' DF in % on a scale of its own (0 to a
round maximum over the analysis' DF grids), with iso-DF lines, and the legend in % with the
DF verdict. The values are the DF grids' daylight factors as the results reader gives them
(lighting.daylight_results, docs/scene-format.md, "Results"); coloring.refresh calls in here."""
from __future__ import annotations

from typing import Any, Dict, Optional

from lighting import daylight_results
from lighting.objects import analysis as analysis_mod
from lighting.objects import results as results_mod


class Daylight:
    """The DF results of one analysis' results object, ready to paint."""

    def __init__(self, analysis: Any, found: Optional[Any]) -> None:
        self.document: Optional[Dict[str, Any]] = results_mod.data(found) if found else None
        self.names = [t.Name for t in analysis_mod.targets(analysis)]
        self.scale = daylight_results.scale(self.document, self.names,
                                            str(getattr(analysis, "ColorMap", "Rainbow")))

    def paint(self, target: Any) -> bool:
        """Paint a DF grid's cells; False (nothing done) for other targets."""
        from lighting.viewproviders import coloring

        found = daylight_results.of_target(self.document, target.Name)
        vobj = getattr(target, "ViewObject", None)
        if found is None or self.scale is None or vobj is None or target.Shape.isNull():
            return False
        cells = daylight_results.cells_percent(found)
        faces = len(target.Shape.Faces)
        proxy = getattr(vobj, "Proxy", None)
        if hasattr(proxy, "set_unlit"):
            proxy.set_unlit(True)
        if hasattr(proxy, "set_isolux"):
            proxy.set_isolux(*coloring.isolux_polylines(target, self.scale, cells))
        if len(cells) == faces:
            colours = self.scale.colours(cells)
        else:
            colours = [self.scale.colour(float(found.mean.value or 0.0))] * faces
        coloring._show(vobj, colours[0], colours, 0)
        return True

    def legend(self) -> Dict[str, Any]:
        """update_legend's title and digits for the DF scale."""
        word = daylight_results.overall_verdict(self.document, self.names)
        title = daylight_results.LEGEND_TITLE + (f" - requirements: {word}" if word else "")
        span = self.scale.max_lux - self.scale.min_lux if self.scale is not None else 0.0
        return {"title": title, "digits": 1 if span < 20.0 else 0}
