# SPDX-License-Identifier: LGPL-2.1-or-later
"""Iso-lux lines of a calculation grid: their levels and their polylines (App code).

Cell values sit at the cell centres; contourpy (the library behind matplotlib's contours)
traces the lines through them, so the 3D view (viewproviders/target.py) and the plan view
(lighting/plots.py, which lets matplotlib call contourpy with the same levels) agree."""
from __future__ import annotations

import math
from typing import List, Sequence, Tuple

import numpy as np

from lighting.colormap import Scale

#: Steps of "nice" levels within a decade.
_NICE_STEPS = (1.0, 2.0, 2.5, 5.0, 10.0)


def nice_levels(low: float, high: float, count: int = 5) -> List[float]:
    """About ``count`` round levels (1, 2, 2.5, 5 x 10^k apart) strictly between low and high."""
    if not (math.isfinite(low) and math.isfinite(high)) or high <= low:
        return []
    raw = (high - low) / max(count, 1)
    exponent = math.floor(math.log10(raw))
    step = next(s * 10.0 ** exponent for s in _NICE_STEPS if s * 10.0 ** exponent >= raw)
    first = math.floor(low / step) + 1
    levels = []
    k = first
    while k * step < high:
        levels.append(round(k * step, 10))
        k += 1
    return levels


def levels(scale: Scale, values: Sequence[float], ticks: int = 6) -> List[float]:
    """The legend's tick values strictly inside the range of ``values``; when fewer than two
    fall inside (a dim wall on a scale made for the work plane), round levels in the range."""
    finite = [float(v) for v in values if math.isfinite(v)]
    if len(finite) < 2:
        return []
    low, high = min(finite), max(finite)
    inside = [t for t in scale.ticks(ticks) if low < t < high]
    return inside if len(inside) >= 2 else nice_levels(low, high)


def lines(values: np.ndarray, size_m: Tuple[float, float],
          levels_lux: Sequence[float]) -> List[Tuple[float, np.ndarray]]:
    """Iso-lux polylines of a grid: ``values`` of shape (nv, nu) at the cell centres of a
    ``size_m`` = (u, v) metres rectangle; returns (level, array of (u, v) points in metres)
    per polyline. Grids under 2 x 2 cells have none."""
    import contourpy

    z = np.asarray(values, dtype=float)
    if z.ndim != 2 or min(z.shape) < 2 or not levels_lux:
        return []
    nv, nu = z.shape
    x = (np.arange(nu) + 0.5) * (size_m[0] / nu)
    y = (np.arange(nv) + 0.5) * (size_m[1] / nv)
    generator = contourpy.contour_generator(x, y, z, line_type=contourpy.LineType.Separate)
    found: List[Tuple[float, np.ndarray]] = []
    for level in levels_lux:
        for points in generator.lines(level):
            if len(points) >= 2:
                found.append((float(level), np.asarray(points, dtype=float)))
    return found
