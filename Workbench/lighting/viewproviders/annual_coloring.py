# SPDX-License-Identifier: LGPL-2.1-or-later
"""Paint the annual daylight maps (GUI only): each grid of an analysis that has annual
results shows, cell by cell, what the annual object's ``Map`` chooses (DA300 or UDI 100-2000
lx as fractions of occupied hours, ASE hours, or the sDA verdict per cell in three colours:
pass, undecided, fail), with its legend. The values come from lighting.annual_results (the
stored summary read through lightsolver_results.read_annual); coloring.refresh calls in here.
``Map`` = "Run illuminance" leaves the grids to the analysis' own run."""
from __future__ import annotations

from typing import Any, Dict, Optional

from lighting import annual_results
from lighting.objects import annual as annual_mod


class Annual:
    """The annual maps of one analysis, ready to paint (``active`` False: nothing to paint)."""

    def __init__(self, analysis: Any) -> None:
        found = [a for a in annual_mod.of_analysis(analysis) if a.SummaryJson]
        self.obj: Optional[Any] = found[0] if found else None
        self.kind = str(self.obj.Map) if self.obj is not None else ""
        self.typed = annual_results.read(annual_mod.summary(self.obj)) \
            if self.obj is not None and self.kind in annual_results.LEGEND else None
        self.color_map = str(getattr(analysis, "ColorMap", "Rainbow"))
        values = [v for g in (self.typed.grids if self.typed is not None else [])
                  for v in annual_results.cell_values(g, self.kind)]
        self.scale = annual_results.scale(self.kind, values, self.color_map) \
            if self.typed is not None else None

    @property
    def active(self) -> bool:
        return self.scale is not None

    def paint(self, target: Any) -> bool:
        """Paint a grid's cells with the map; False (nothing done) for targets it lacks."""
        from lighting.viewproviders import coloring

        grid = annual_results.grid_of(self.typed, target.Name) if self.active else None
        vobj = getattr(target, "ViewObject", None)
        if grid is None or vobj is None or target.Shape.isNull():
            return False
        cells = annual_results.cell_values(grid, self.kind)
        faces = len(target.Shape.Faces)
        if len(cells) != faces:
            return False
        proxy = getattr(vobj, "Proxy", None)
        if hasattr(proxy, "set_unlit"):
            proxy.set_unlit(True)
        if hasattr(proxy, "set_isolux"):
            proxy.set_isolux([])  # a map of fractions or verdicts: no iso-lux lines
        colours = self.scale.colours(cells)
        coloring._show(vobj, colours[0], colours, 0)
        return True

    def legend(self) -> Dict[str, Any]:
        """update_legend's title and digits for the map."""
        title, digits = annual_results.LEGEND[self.kind]
        return {"title": f"Annual: {title}", "digits": digits}
