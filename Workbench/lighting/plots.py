# SPDX-License-Identifier: LGPL-2.1-or-later
"""Plan views of calculation grids as images (App code, matplotlib's Agg backend, no GUI).

A grid's results are drawn as seen from its front: cells in false colours with the
analysis' colour map and scale (the 3D view's colours), iso-lux lines at the levels of
lighting.isolux, cell values where they fit, the grid's axes in metres and a caption with
Em, Emin, U0 and the requirement. The task panel's plan view (taskpanels/plan_view.py)
shows these images; :func:`save_grid_png` writes one for reports, headless.

matplotlib is imported inside the functions: importing this module stays cheap."""
from __future__ import annotations

import io
import math
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from lighting import isolux
from lighting.colormap import Scale, auto_scale, colour, requirement_scale
from lighting.objects import analysis as analysis_mod
from lighting.objects import results as results_mod
from lighting.objects.base import objects_of_type

#: Cell text height in points; values are written when a cell is at least this wide (px).
VALUE_FONT_PT = 6.5
_MIN_CELL_PX = (36.0, 14.0)


@dataclass
class GridPlot:
    """What a plan view of one grid shows (lux, metres)."""

    label: str
    surface: str
    size_m: Tuple[float, float]
    lux: np.ndarray  # shape (nv, nu), row iv along edge2
    mean_lux: float
    min_lux: float
    max_lux: float
    uniformity: float
    #: The requirements judged (Em, U0; 0: none), as the verdicts state them.
    required_lux: float = 0.0
    required_uniformity: float = 0.0
    axis_names: Tuple[str, str] = ("u", "v")
    origin_m: Tuple[float, float] = (0.0, 0.0)
    #: The verdict by requirement ("em", "u0": "pass", "fail" or "undecided"), as the results
    #: reader gives it (lightsolver_results.Target.verdict_of).
    verdicts: Optional[Dict[str, str]] = None
    #: The verdicts are the reader's point estimates (results without the solver's verdicts
    #: for this grid), not the solver's from the intervals.
    estimated: bool = False

    def _judged(self, key: str) -> str:
        """The verdict on one requirement as the caption words it."""
        found = (self.verdicts or {}).get(key)
        if found is None:
            return "not judged"
        if self.estimated:
            return "met (estimate)" if found == "pass" else "NOT met (estimate)"
        return {"pass": "pass", "fail": "FAIL"}.get(found, "undecided")

    def caption(self) -> str:
        """Em, Emin, Emax and U0, and the requirement when there is one."""
        text = (f"Em {self.mean_lux:.0f} lx   Emin {self.min_lux:.0f} lx   "
                f"Emax {self.max_lux:.0f} lx   U0 {self.uniformity:.2f}")
        needs = []
        if self.required_lux > 0:
            needs.append(f"Em \u2265 {self.required_lux:g} lx ({self._judged('em')})")
        if self.required_uniformity > 0:
            needs.append(f"U0 \u2265 {self.required_uniformity:g} ({self._judged('u0')})")
        return text + (f"\nrequired: {', '.join(needs)}" if needs else "")


def required_lux(analysis: Any) -> List[float]:
    """The Em requirements (lx) of the analysis' targets as the document holds them now."""
    return [float(entry.get("em_lux", 0.0))
            for entry in analysis_mod.requirements(analysis).values()]


def requirement_range(analysis: Any) -> Optional[Tuple[float, float]]:
    """The scale of ScaleMode "Requirements": 0 to a round 1.5 x the highest required Em
    (colormap.requirement_scale); None when no target has an Em requirement."""
    return requirement_scale(required_lux(analysis))


def analysis_scale(analysis: Any) -> Scale:
    """The colour scale of an analysis (Requirements: 0 to 1.5 x the highest required Em, the
    same for every run; Fixed: ScaleMinLux..ScaleMaxLux; Auto, and Requirements without any
    requirement: 0 to a round maximum over its targets' means and cells), as the 3D view and
    its legend use it."""
    if analysis.ScaleMode == "Fixed":
        return Scale(float(analysis.ScaleMinLux), float(analysis.ScaleMaxLux), analysis.ColorMap)
    if analysis.ScaleMode == "Requirements":
        fixed = requirement_range(analysis)
        if fixed is not None:
            return Scale(fixed[0], fixed[1], analysis.ColorMap)
    values: List[float] = []
    found = results_mod.of_analysis(analysis)
    if found is not None:
        for tgt in analysis_mod.targets(analysis):
            mean = results_mod.mean_lux(found, tgt.Name)
            if mean is not None:
                values.append(mean)
                values.extend(results_mod.cells_lux(found, tgt.Name))
    low, high = auto_scale(values)
    return Scale(low, high, analysis.ColorMap)


def scale_note(analysis: Any) -> Tuple[bool, str]:
    """(locked, text) for the legend: whether the scale stays the same from run to run, and
    where it comes from, in the user's words."""
    mode = analysis.ScaleMode
    if mode == "Fixed":
        return True, (f"Locked: {float(analysis.ScaleMinLux):.0f}-"
                      f"{float(analysis.ScaleMaxLux):.0f} lx, set by you")
    if mode == "Requirements":
        top = max(required_lux(analysis), default=0.0)
        fixed = requirement_range(analysis)
        if fixed is not None:
            return True, (f"Locked: 0-{fixed[1]:.0f} lx, from the requirements "
                          f"(1.5 x {top:.0f} lx required, rounded up)")
        return False, "Follows each run: no target has an Em requirement to set it from"
    return False, "Follows each run (Auto): colours of two runs are not comparable"


def _axis(direction: Any, origin_mm: float) -> Tuple[str, float]:
    """Name and offset (m) of an edge running along a global axis (x, y, z), else ('', 0)."""
    for name, component in (("x", direction.x), ("y", direction.y), ("z", direction.z)):
        if component > 1.0 - 1e-9:
            return name, origin_mm / 1000.0
    return "", 0.0


def grid_plot_data(analysis: Any, target: Any) -> Optional[GridPlot]:
    """The plan-view data of a grid target from the analysis' results object; None when it
    has no results there or its cells no longer match the grid (the model changed)."""
    from lighting.objects import target as target_mod

    found = results_mod.of_analysis(analysis)
    index = results_mod.index_of(found, target.Name) if found is not None else None
    if index is None or getattr(target, "TargetType", "") != "Grid":
        return None
    typed = results_mod.read(results_mod.data(found), analysis_mod.requirements(analysis))
    judged = next((t for t in typed.targets if t.name == target.Name), None) if typed else None
    if judged is None:
        return None
    try:
        rect = target_mod.grid_rectangle(target)
    except ValueError:
        return None
    cells = results_mod.cells_lux(found, target.Name)
    if len(cells) != rect.nu * rect.nv or not cells:
        return None
    u_dir, v_dir = rect.axes()
    (u_name, u0), (v_name, v0) = (_axis(u_dir, rect.corner.dot(u_dir)),
                                  _axis(v_dir, rect.corner.dot(v_dir)))
    names = (u_name, v_name) if u_name and v_name else ("u", "v")
    origin = (u0, v0) if u_name and v_name else (0.0, 0.0)
    return GridPlot(label=target.Label, surface=getattr(target, "Surface", "Work plane"),
                    size_m=rect.size_m, lux=np.asarray(cells, float).reshape(rect.nv, rect.nu),
                    mean_lux=float(found.MeanLux[index]), min_lux=float(found.MinLux[index]),
                    max_lux=float(found.MaxLux[index]), uniformity=float(found.Uniformity[index]),
                    required_lux=float(judged.requirements.get("em_lux", 0.0)),
                    required_uniformity=float(judged.requirements.get("u0", 0.0)),
                    axis_names=names, origin_m=origin,
                    verdicts={key: word for key in ("em", "u0")
                              if (word := judged.verdict_of(key)) is not None},
                    estimated=judged.estimated)


def _colormap(scale: Scale) -> Any:
    from matplotlib.colors import ListedColormap

    return ListedColormap([colour(i / 255.0, scale.name) for i in range(256)])


def grid_figure(data: GridPlot, scale: Scale, width_px: int = 800, dpi: int = 100) -> Any:
    """A matplotlib Figure (not registered with pyplot) of one grid's plan view."""
    from matplotlib.colors import Normalize
    from matplotlib.figure import Figure

    lu, lv = data.size_m
    width_in = width_px / dpi
    plot_in = width_in * 0.78
    height_in = min(max(plot_in * lv / lu, 1.0), 3.0 * width_in) + 1.35
    fig = Figure(figsize=(width_in, height_in), dpi=dpi, layout="constrained")
    ax = fig.add_subplot()
    (x0, y0), (nv, nu) = data.origin_m, data.lux.shape
    xs, ys = x0 + np.linspace(0.0, lu, nu + 1), y0 + np.linspace(0.0, lv, nv + 1)
    norm = Normalize(vmin=scale.min_lux, vmax=scale.max_lux)
    mesh = ax.pcolormesh(xs, ys, data.lux, cmap=_colormap(scale), norm=norm,
                         edgecolors=(0, 0, 0, 0.15), linewidth=0.3)
    levels = isolux.levels(scale, data.lux.ravel())
    if levels and min(nu, nv) >= 2:
        xc, yc = 0.5 * (xs[1:] + xs[:-1]), 0.5 * (ys[1:] + ys[:-1])
        lines = ax.contour(xc, yc, data.lux, levels=levels, colors="k", linewidths=0.9)
        ax.clabel(lines, fmt="%g", fontsize=VALUE_FONT_PT + 0.5, inline=True)
    _cell_values(fig, ax, data, scale, xs, ys, dpi)
    ax.set_aspect("equal")
    ax.set_xlim(xs[0], xs[-1])
    ax.set_ylim(ys[0], ys[-1])
    ax.set_xlabel(f"{data.axis_names[0]} [m]", fontsize=8)
    ax.set_ylabel(f"{data.axis_names[1]} [m]", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.set_title(f"{data.label} ({data.surface.lower()})", fontsize=9)
    bar = fig.colorbar(mesh, ax=ax, shrink=0.9, pad=0.02)
    bar.ax.tick_params(labelsize=7)
    bar.set_label("lx", fontsize=7)
    fig.supxlabel(_wrapped(data.caption(), width_px), fontsize=7.5)
    return fig


def _wrapped(text: str, width_px: int) -> str:
    """The caption's lines wrapped to the figure's width (about 5.5 px per character at
    7.5 pt and 100 dpi), so a narrow panel shows all of it."""
    import textwrap

    chars = max(int(width_px / 5.5), 20)
    return "\n".join(textwrap.fill(line, chars, break_on_hyphens=False)
                     for line in text.splitlines())


def _cell_values(fig: Any, ax: Any, data: GridPlot, scale: Scale, xs: np.ndarray,
                 ys: np.ndarray, dpi: int) -> None:
    """Write each cell's value in it when cells are large enough on the figure."""
    nv, nu = data.lux.shape
    fig_w, fig_h = fig.get_size_inches() * dpi
    lu, lv = data.size_m
    # The axes get roughly 78 % of the width; equal aspect fixes the height.
    cell_w = 0.78 * fig_w / nu
    cell_h = cell_w * (lv / nv) / (lu / nu)
    digits = len(f"{np.nanmax(data.lux):.0f}") if np.isfinite(data.lux).any() else 1
    if cell_w < max(_MIN_CELL_PX[0], 6.0 * digits + 6.0) or cell_h < _MIN_CELL_PX[1]:
        return
    for iv in range(nv):
        for iu in range(nu):
            value = data.lux[iv, iu]
            if math.isfinite(value):
                r, g, b = scale.colour(value)
                dark = 0.299 * r + 0.587 * g + 0.114 * b < 0.45  # white text on dark cells
                ax.text(0.5 * (xs[iu] + xs[iu + 1]), 0.5 * (ys[iv] + ys[iv + 1]),
                        f"{value:.0f}", ha="center", va="center", fontsize=VALUE_FONT_PT,
                        color=(1, 1, 1) if dark else (0.1, 0.1, 0.1))


def grid_png(data: GridPlot, scale: Scale, path: Optional[str] = None, width_px: int = 800,
             dpi: int = 100) -> bytes:
    """Render a plan view to PNG bytes (Agg), and write them to ``path`` when given."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig = grid_figure(data, scale, width_px=width_px, dpi=dpi)
    canvas = FigureCanvasAgg(fig)
    buffer = io.BytesIO()
    canvas.print_png(buffer)
    png = buffer.getvalue()
    if path is not None:
        from lighting.files import write_bytes

        write_bytes(path, png)  # atomic: a failed write keeps the old file
    return png


def save_grid_png(target: Any, path: str, analysis: Optional[Any] = None,
                  width_px: int = 1000) -> str:
    """Write the plan view of a grid target's stored results to a PNG file; returns the path.

    ``analysis`` defaults to the one whose results hold the target. Raises ValueError naming
    the target when it is not a grid or has no results."""
    if analysis is None:
        analysis = next((a for a in objects_of_type(target.Document, analysis_mod.TYPE)
                         if grid_plot_data(a, target) is not None), None)
    data = grid_plot_data(analysis, target) if analysis is not None else None
    if data is None:
        raise ValueError(f"Grid target '{target.Label}' has no results to plot (is it a grid, "
                         "and was the analysis run since the grid changed?)")
    grid_png(data, analysis_scale(analysis), path=path, width_px=width_px)
    return path
