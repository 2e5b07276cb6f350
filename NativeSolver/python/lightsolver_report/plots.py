# SPDX-License-Identifier: LGPL-2.1-or-later
"""The report's pictures as SVG text (matplotlib, no pyplot state): a false-colour plan of a
grid with iso-lux lines (matplotlib's contour, i.e. contourpy) and a value chart (the lux of
every cell). Byte-stable: ids come from ``svg.hashsalt`` (one salt per picture, so ids are
unique within the HTML page), no date or creator is written, text stays text."""
from __future__ import annotations

import io
import re
from typing import Callable, Dict, List, Optional, Tuple

import numpy as np

from lightsolver_report.fmt import lux as fmt_lux
from lightsolver_report.model import GridData

#: The workbench's "Rainbow" false-colour map (Workbench/lighting/colormap.py), so the report's
#: plans and the 3D view use the same colours.
RAINBOW = ((0.0, (0.0, 0.0, 0.55)), (0.15, (0.0, 0.2, 1.0)), (0.35, (0.0, 0.85, 1.0)),
           (0.5, (0.1, 0.9, 0.2)), (0.65, (1.0, 1.0, 0.0)), (0.85, (1.0, 0.45, 0.0)),
           (1.0, (0.85, 0.0, 0.0)))
#: Width of a picture on the page (A4 with 18 mm margins), inches.
PAGE_WIDTH_IN = 6.7
#: Most value labels a chart prints along u and v; larger grids show every k-th cell.
MAX_LABELS_U, MAX_LABELS_V = 24, 40
#: Above this many cells the plan's cells are embedded as one image, not one path each.
RASTER_CELLS = 4096
FONT = "DejaVu Sans"


def _rc(salt: str) -> Dict[str, object]:
    return {"svg.hashsalt": salt, "svg.fonttype": "none", "font.family": FONT, "font.size": 8.0,
            "axes.linewidth": 0.6, "xtick.major.width": 0.6, "ytick.major.width": 0.6,
            "path.simplify": False}


def _svg(fig, salt: str, dpi: Optional[float] = None) -> str:
    """The figure as an inline ``<svg>`` element (no XML prolog, no date); ``dpi`` is the
    resolution of its rasterized parts (default: the figure's)."""
    import matplotlib

    buffer = io.StringIO()
    with matplotlib.rc_context(_rc(salt)):
        fig.savefig(buffer, format="svg", dpi=dpi or "figure",
                    metadata={"Date": None, "Creator": None})
    text = buffer.getvalue()
    text = _FONT_SHORTHAND.sub(_font_longhand, text[text.index("<svg"):].strip())
    return _prefix_ids(text, salt)


def _prefix_ids(svg: str, prefix: str) -> str:
    """Prefix every id (and the references to it) so that several pictures can share a page:
    matplotlib names the groups of every figure alike (figure_1, axes_1...)."""
    ids = set(re.findall(r'\sid="([^"]+)"', svg))
    svg = re.sub(r'(\sid=")([^"]+)"', lambda m: f'{m.group(1)}{prefix}-{m.group(2)}"', svg)
    return re.sub(r'(url\(#|href="#)([^)"]+)',
                  lambda m: f"{m.group(1)}{prefix}-{m.group(2)}" if m.group(2) in ids
                  else m.group(0), svg)


#: matplotlib's ``font: [weight] SIZEpx FAMILIES`` shorthand, which WeasyPrint's SVG renderer
#: does not read (it then draws text at its default size).
_FONT_SHORTHAND = re.compile(r"font: (?:(\w+) )?([\d.]+)px ([^;\"]+)")


def _font_longhand(match: "re.Match[str]") -> str:
    weight = f"font-weight: {match.group(1)}; " if match.group(1) else ""
    family = match.group(3).split(",")[0].strip()
    return f"{weight}font-size: {match.group(2)}px; font-family: {family}"


def _figure(width_in: float, height_in: float):
    from matplotlib.figure import Figure

    return Figure(figsize=(width_in, height_in))


def colormap():
    """The false-colour map as a matplotlib colormap."""
    from matplotlib.colors import LinearSegmentedColormap

    return LinearSegmentedColormap.from_list("lightsolver_rainbow", list(RAINBOW))


def colour_range(values: np.ndarray) -> Tuple[float, float]:
    """The colour scale: round numbers at or around the smallest and largest value, so the
    colours spread over the values the grid has (0 to 1 lx for a dark grid)."""
    from matplotlib.ticker import MaxNLocator

    low, high = (float(np.min(values)), float(np.max(values))) if values.size else (0.0, 0.0)
    if high <= 0.0:
        return 0.0, 1.0
    if high - low < 1e-9 * high:
        low, high = 0.9 * low, 1.1 * high
    ticks = MaxNLocator(nbins=6, steps=[1, 2, 2.5, 5, 10]).tick_values(low, high)
    return float(max(0.0, ticks[0])), float(max(ticks[-1], high))


def iso_levels(values: np.ndarray, count: int = 6) -> List[float]:
    """About ``count`` round iso-lux levels strictly between the smallest and largest cell."""
    from matplotlib.ticker import MaxNLocator

    low, high = float(np.min(values)), float(np.max(values))
    if not high > low:
        return []
    ticks = MaxNLocator(nbins=count, steps=[1, 2, 2.5, 5, 10]).tick_values(low, high)
    return [float(t) for t in ticks if low < t < high]


def _size(grid: GridData, extra_w: float, max_h: float = 4.6) -> Tuple[float, float]:
    """Figure size keeping the grid's aspect ratio, the grid at most the page width wide."""
    plot_w = PAGE_WIDTH_IN - extra_w
    plot_h = plot_w * grid.size_v_m / grid.size_u_m
    if plot_h > max_h:
        plot_h = max_h
        plot_w = plot_h * grid.size_u_m / grid.size_v_m
    return plot_w, plot_h


def _edges(grid: GridData) -> Tuple[np.ndarray, np.ndarray]:
    nv, nu = grid.lux.shape
    return (grid.origin_u_m + np.linspace(0.0, grid.size_u_m, nu + 1),
            grid.origin_v_m + np.linspace(0.0, grid.size_v_m, nv + 1))


def _axes(fig, grid: GridData, left_in: float, bottom_in: float, w_in: float, h_in: float):
    width, height = fig.get_size_inches()
    ax = fig.add_axes((left_in / width, bottom_in / height, w_in / width, h_in / height))
    ax.set_xlim(grid.origin_u_m, grid.origin_u_m + grid.size_u_m)
    ax.set_ylim(grid.origin_v_m, grid.origin_v_m + grid.size_v_m)
    ax.set_xlabel(f"{grid.axis_u} [m]")
    ax.set_ylabel(f"{grid.axis_v} [m]")
    ax.tick_params(labelsize=7, length=3)
    return ax


def _extreme_cell(grid: GridData, which) -> Tuple[float, float, float, float]:
    """(u0, v0, du, dv) of the first cell holding the min (or max) value."""
    nv, nu = grid.lux.shape
    iv, iu = np.unravel_index(int(which(grid.lux)), grid.lux.shape)
    du, dv = grid.size_u_m / nu, grid.size_v_m / nv
    return grid.origin_u_m + iu * du, grid.origin_v_m + iv * dv, du, dv


def df_text(value: float) -> str:
    """A daylight factor in a chart cell: two decimals below 10 %, one above."""
    return f"{value:.2f}" if abs(value) < 10 else f"{value:.1f}"


def plan_svg(grid: GridData, salt: str, quantity: str = "E [lx]") -> str:
    """False-colour plan: cells in colour (0 to a round maximum), iso-lines labelled in the
    grid's unit (lux; percent for a daylight factor), the cell of the minimum outlined, a colour
    bar labelled ``quantity``."""
    from matplotlib.colors import Normalize
    from matplotlib.patches import Rectangle

    plot_w, plot_h = _size(grid, extra_w=1.6, max_h=2.75)
    left, bottom = 0.55, 0.42
    fig = _figure(left + plot_w + 1.05, bottom + plot_h + 0.12)
    ax = _axes(fig, grid, left, bottom, plot_w, plot_h)
    norm = Normalize(*colour_range(grid.lux))
    u_edges, v_edges = _edges(grid)
    mesh = ax.pcolormesh(u_edges, v_edges, grid.lux, cmap=colormap(), norm=norm,
                         shading="flat", rasterized=grid.lux.size > RASTER_CELLS)
    nv, nu = grid.lux.shape
    levels = iso_levels(grid.lux)
    if nu >= 2 and nv >= 2 and levels:
        uc = 0.5 * (u_edges[:-1] + u_edges[1:])
        vc = 0.5 * (v_edges[:-1] + v_edges[1:])
        lines = ax.contour(uc, vc, grid.lux, levels=levels, colors="black", linewidths=0.7)
        ax.clabel(lines, fmt=lambda v: f"{v:g}", fontsize=6.5, inline=True, inline_spacing=2)
    u0, v0, du, dv = _extreme_cell(grid, np.argmin)
    ax.add_patch(Rectangle((u0, v0), du, dv, fill=False, edgecolor="white", linewidth=1.6))
    ax.add_patch(Rectangle((u0, v0), du, dv, fill=False, edgecolor="black", linewidth=0.8,
                           linestyle=(0, (2, 1.5))))
    width, height = fig.get_size_inches()
    cax = fig.add_axes(((left + plot_w + 0.18) / width, bottom / height, 0.14 / width,
                        plot_h / height))
    bar = fig.colorbar(mesh, cax=cax)
    bar.set_label(quantity, fontsize=7)
    bar.ax.tick_params(labelsize=7, length=2)
    bar.outline.set_linewidth(0.6)
    return _svg(fig, salt)


def _ordinal(k: int) -> str:
    return f"{k}{'nd' if k == 2 else 'rd' if k == 3 else 'th'}"


def _stride(n: int, most: int) -> int:
    return max(1, -(-n // most))


def chart_svg(grid: GridData, salt: str,
              text: Callable[[float], str] = fmt_lux) -> Tuple[str, str]:
    """Value chart: the grid's cells with their value written in them (``text``: lux by
    default; every k-th cell of large grids), the minimum bold on grey, the maximum bold.
    Returns the SVG and a note on what it shows."""
    from matplotlib.patches import Rectangle

    nv, nu = grid.lux.shape
    su, sv = _stride(nu, MAX_LABELS_U), _stride(nv, MAX_LABELS_V)
    plot_w, plot_h = _size(grid, extra_w=1.6, max_h=2.75)
    # Enough height per printed row for the text.
    rows = -(-nv // sv)
    if plot_h / rows < 0.16:
        plot_h = min(7.0, 0.16 * rows)
    left, bottom = 0.55, 0.42
    fig = _figure(left + plot_w + 0.15, bottom + plot_h + 0.12)
    ax = _axes(fig, grid, left, bottom, plot_w, plot_h)
    u_edges, v_edges = _edges(grid)
    du, dv = grid.size_u_m / nu, grid.size_v_m / nv
    i_min = np.unravel_index(int(np.argmin(grid.lux)), grid.lux.shape)
    i_max = np.unravel_index(int(np.argmax(grid.lux)), grid.lux.shape)
    ax.add_patch(Rectangle((u_edges[i_min[1]], v_edges[i_min[0]]), du, dv, facecolor="#d9d9d9",
                           edgecolor="none"))
    if su == 1 and sv == 1:
        for u in u_edges[1:-1]:
            ax.axvline(u, color="#c8c8c8", linewidth=0.4)
        for v in v_edges[1:-1]:
            ax.axhline(v, color="#c8c8c8", linewidth=0.4)
    cell_w_pt = 72.0 * plot_w / nu * su
    size = float(min(7.0, max(4.0, cell_w_pt / 4.2)))
    shown = set()
    for iv in range(0, nv, sv):
        for iu in range(0, nu, su):
            shown.add((iv, iu))
    shown.update({tuple(int(i) for i in i_min), tuple(int(i) for i in i_max)})
    for iv, iu in sorted(shown):
        bold = (iv, iu) in (tuple(i_min), tuple(i_max))
        ax.text(u_edges[iu] + 0.5 * du, v_edges[iv] + 0.5 * dv, text(float(grid.lux[iv, iu])),
                ha="center", va="center", fontsize=size, fontweight="bold" if bold else "normal")
    parts = ([f"every {_ordinal(su)} column"] if su > 1 else []) + (
        [f"every {_ordinal(sv)} row"] if sv > 1 else [])
    note = " and ".join(parts) + " (and the Emin and Emax cells)" if parts else "every cell"
    return _svg(fig, salt), note
