# SPDX-License-Identifier: LGPL-2.1-or-later
"""The results' ``sunlight_exposure`` (EN 17037 hours of possible sunlight at window reference
points, docs/scene-format.md "Sunlight exposure (EN 17037)") as a typed view."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

from .layout import finite

#: The solver's levels in the standard's order (docs/daylight.md): none below 1.5 h.
LEVELS = ("none", "minimum", "medium", "high")


@dataclass(frozen=True)
class SunlightPoint:
    """One reference point: its hours of possible sunlight, EN 17037 level and the periods
    (local ``hh:mm`` pairs)."""

    name: str
    hours: Optional[float]  # None where the results give no number
    level: str
    periods: Tuple[Tuple[str, str], ...] = ()

    def duration_text(self) -> str:
        """The hours as ``3 h 12 min`` (rounded to the minute); "–" without a number."""
        if self.hours is None:
            return "–"
        minutes = int(round(self.hours * 60.0))
        return f"{minutes // 60} h {minutes % 60:02d} min"


@dataclass(frozen=True)
class SunlightExposureView:
    """The day, its step, the minimum solar altitude and each point's result."""

    date: str
    step_minutes: Optional[float]
    min_elevation_deg: Optional[float]
    points: List[SunlightPoint] = field(default_factory=list)


def sunlight_view(doc: Dict[str, Any]) -> Optional[SunlightExposureView]:
    """The view of ``doc['sunlight_exposure']``; None when the results have none."""
    entry = doc.get("sunlight_exposure")
    if not isinstance(entry, dict):
        return None
    points = []
    for point in entry.get("points", []):
        if not isinstance(point, dict):
            continue
        hours = finite(point.get("hours"))
        level = str(point.get("level", "none"))
        periods = tuple((str(p[0]), str(p[1])) for p in point.get("periods", [])
                        if isinstance(p, (list, tuple)) and len(p) == 2)
        points.append(SunlightPoint(str(point.get("name", "")), hours,
                                    level if level in LEVELS else "none", periods))
    return SunlightExposureView(str(entry.get("date", "")), finite(entry.get("step_minutes")),
                                finite(entry.get("min_elevation_deg")), points)
