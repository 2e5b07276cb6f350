# SPDX-License-Identifier: LGPL-2.1-or-later
"""False-colour maps and scales for illuminance (pure Python, testable headless)."""
from __future__ import annotations

import math
from typing import Iterable, List, Optional, Sequence, Tuple

RGB = Tuple[float, float, float]

#: Control points (position 0..1, colour) of each map; linear in between.
MAPS = {
    "Rainbow": ((0.0, (0.0, 0.0, 0.55)), (0.15, (0.0, 0.2, 1.0)), (0.35, (0.0, 0.85, 1.0)),
                (0.5, (0.1, 0.9, 0.2)), (0.65, (1.0, 1.0, 0.0)), (0.85, (1.0, 0.45, 0.0)),
                (1.0, (0.85, 0.0, 0.0))),
    "Heat": ((0.0, (0.0, 0.0, 0.0)), (0.35, (0.75, 0.0, 0.0)), (0.7, (1.0, 0.65, 0.0)),
             (1.0, (1.0, 1.0, 0.85))),
    "Grey": ((0.0, (0.05, 0.05, 0.05)), (1.0, (1.0, 1.0, 1.0))),
}


def colour(t: float, name: str = "Rainbow") -> RGB:
    """Colour of position ``t`` (0..1, clamped) on the map ``name``."""
    points = MAPS.get(name, MAPS["Rainbow"])
    if not math.isfinite(t):
        t = 0.0
    t = min(max(t, 0.0), 1.0)
    for (t0, c0), (t1, c1) in zip(points, points[1:]):
        if t <= t1:
            f = 0.0 if t1 == t0 else (t - t0) / (t1 - t0)
            return (c0[0] + f * (c1[0] - c0[0]), c0[1] + f * (c1[1] - c0[1]),
                    c0[2] + f * (c1[2] - c0[2]))
    return points[-1][1]


def nice_max(value: float) -> float:
    """A round number >= value (1, 1.5, 2, 2.5, 3, 4, 5, 6, 7.5, 8 x 10^k) for the top of an
    automatic scale: 640 lx -> 750 lx."""
    if value <= 0.0 or not math.isfinite(value):
        return 1.0
    exponent = math.floor(math.log10(value))
    for step in (1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 7.5, 8.0, 10.0):
        candidate = step * 10.0 ** exponent
        if candidate >= value * (1.0 - 1e-12):
            return candidate
    return 10.0 ** (exponent + 1)


def auto_scale(values: Iterable[float]) -> Tuple[float, float]:
    """(0, a round maximum) covering all values."""
    top = max((v for v in values if math.isfinite(v)), default=0.0)
    return 0.0, nice_max(top)


#: The top of a scale set from the requirements: this times the highest required Em, rounded
#: up (nice_max), so a target that just meets its requirement sits at two thirds of the scale.
REQUIREMENT_HEADROOM = 1.5


def requirement_scale(required_lux: Iterable[float]) -> Optional[Tuple[float, float]]:
    """(0, a round 1.5 x the highest required Em) or None without any positive requirement: a
    scale that stays the same from run to run, so a darker result always looks darker."""
    top = max((v for v in required_lux if math.isfinite(v) and v > 0.0), default=0.0)
    if top <= 0.0:
        return None
    return 0.0, nice_max(REQUIREMENT_HEADROOM * top)


class Scale:
    """Maps illuminance (lx) to colours between ``min_lux`` and ``max_lux``."""

    def __init__(self, min_lux: float, max_lux: float, name: str = "Rainbow") -> None:
        if max_lux <= min_lux:
            max_lux = min_lux + 1.0
        self.min_lux = min_lux
        self.max_lux = max_lux
        self.name = name

    def position(self, lux: float) -> float:
        """Position 0..1 of a value on the scale (clamped)."""
        return min(max((lux - self.min_lux) / (self.max_lux - self.min_lux), 0.0), 1.0)

    def colour(self, lux: float) -> RGB:
        """Colour of an illuminance value."""
        return colour(self.position(lux), self.name)

    def colours(self, values: Sequence[float]) -> List[RGB]:
        """Colours of many values."""
        return [self.colour(v) for v in values]

    def ticks(self, count: int = 6) -> List[float]:
        """``count`` evenly spaced values from min to max for the legend."""
        count = max(count, 2)
        step = (self.max_lux - self.min_lux) / (count - 1)
        return [self.min_lux + i * step for i in range(count)]
