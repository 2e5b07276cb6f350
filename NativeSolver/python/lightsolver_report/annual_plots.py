# SPDX-License-Identifier: LGPL-2.1-or-later
"""The annual section's plans (docs/report.md, "A year of daylight"): DA300 per cell on a fixed
0–100 % scale with the 50 % line (sDA's threshold) and the cells whose sDA verdict is undecided
marked "?", and the occupied hours of direct sun per cell with the 250 h line (ASE's). Drawn
with the false-colour plan's rules (plots.py: matplotlib without pyplot, byte-stable SVG)."""
from __future__ import annotations

from typing import Any, Optional

import numpy as np

from lightsolver_report import plots
from lightsolver_report.annual import AnnualGridView, grid_extent
from lightsolver_report.model import GridData


def _grid(view: AnnualGridView, values: np.ndarray) -> GridData:
    u0, v0, su, sv, au, av = grid_extent(view.geometry or {})
    return GridData(values, su, sv, u0, v0, au, av)


def _plan(grid: GridData, vmin: float, vmax: float, level: Optional[float], level_text: str,
          quantity: str, marks: Optional[np.ndarray] = None) -> Any:
    """The figure: cells coloured on [vmin, vmax], the line at ``level``, "?" in the cells of
    ``marks``, a colour bar labelled ``quantity``."""
    from matplotlib.colors import Normalize

    plot_w, plot_h = plots._size(grid, extra_w=1.6, max_h=2.75)
    left, bottom = 0.55, 0.42
    fig = plots._figure(left + plot_w + 1.05, bottom + plot_h + 0.12)
    ax = plots._axes(fig, grid, left, bottom, plot_w, plot_h)
    u_edges, v_edges = plots._edges(grid)
    mesh = ax.pcolormesh(u_edges, v_edges, grid.lux, cmap=plots.colormap(),
                         norm=Normalize(vmin, vmax), shading="flat",
                         rasterized=grid.lux.size > plots.RASTER_CELLS)
    nv, nu = grid.lux.shape
    uc = 0.5 * (u_edges[:-1] + u_edges[1:])
    vc = 0.5 * (v_edges[:-1] + v_edges[1:])
    low, high = float(np.min(grid.lux)), float(np.max(grid.lux))
    if level is not None and nu >= 2 and nv >= 2 and low < level < high:
        lines = ax.contour(uc, vc, grid.lux, levels=[level], colors="black", linewidths=1.0)
        ax.clabel(lines, fmt=lambda v: level_text, fontsize=6.5, inline=True, inline_spacing=2)
    if marks is not None:
        size = float(min(7.0, max(4.0, 72.0 * plot_w / nu / 2.2)))
        for iv, iu in zip(*np.nonzero(marks)):
            ax.text(uc[iu], vc[iv], "?", ha="center", va="center", fontsize=size,
                    fontweight="bold", color="black")
    width, height = fig.get_size_inches()
    cax = fig.add_axes(((left + plot_w + 0.18) / width, bottom / height, 0.14 / width,
                        plot_h / height))
    bar = fig.colorbar(mesh, cax=cax)
    bar.set_label(quantity, fontsize=7)
    bar.ax.tick_params(labelsize=7, length=2)
    bar.outline.set_linewidth(0.6)
    return fig


def da_plan_svg(view: AnnualGridView, salt: str) -> str:
    """DA300 in percent per cell, 0–100 %, the 50 % line, undecided cells marked "?"."""
    share = 100.0 * float(view.data.options.get("sda_da_fraction", 0.5))
    threshold = float(view.data.options.get("da_threshold_lx", 300.0))
    fig = _plan(_grid(view, view.da_percent), 0.0, 100.0, share, f"{share:g} %",
                f"DA{threshold:g} [%]", marks=view.undecided)
    return plots._svg(fig, salt)


def ase_plan_svg(view: AnnualGridView, salt: str) -> str:
    """Occupied hours of direct sun above 1000 lx per cell, the 250 h line."""
    hours = view.ase_hours if view.ase_hours is not None else np.zeros_like(view.da_percent)
    limit = float(view.data.options.get("ase_hours", 250))
    top = max(float(np.max(hours)), limit * 1.2)
    _, top = plots.colour_range(np.array([0.0, top]))
    fig = _plan(_grid(view, hours), 0.0, top, limit, f"{limit:g} h", "hours of direct sun")
    return plots._svg(fig, salt)
