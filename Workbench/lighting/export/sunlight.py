# SPDX-License-Identifier: LGPL-2.1-or-later
"""EN 17037 sunlight exposure from a Sky (docs/workbench-daylight.md, "Sunlight exposure";
docs/daylight.md "Sunlight exposure (EN 17037)"; docs/scene-format.md "Sunlight exposure"):
one reference point per window that is a portal of the Sky, and the scene's top-level
``sunlight_exposure`` around them. App code: headless, no GUI import."""
from __future__ import annotations

import datetime
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

from lighting.compat import get_property
from lighting.export.portals import Found, Portal
from lighting.units import vec_m

#: EN 17037's heights of the reference point (mm): above the floor and above the sill.
ABOVE_FLOOR_MM = 1200.0
ABOVE_SILL_MM = 300.0
#: The standard's assessment span (docs/daylight.md): 1 February to 21 March.
SPAN = ((2, 1), (3, 21))


@dataclass(frozen=True)
class ReferencePoint:
    """A window's reference point (mm, global), its outward unit normal and, when the opening
    is too low for EN 17037's heights, why (the point then sits at the opening's centre)."""

    name: str
    position: Any
    normal: Any
    note: str = ""

    def scene_entry(self) -> Dict[str, Any]:
        """The scene's point (metres)."""
        return {"name": self.name, "position": vec_m(self.position),
                "normal": [round(float(c), 12) for c in (self.normal.x, self.normal.y,
                                                           self.normal.z)]}


def floor_z(window: Any) -> Optional[float]:
    """The floor under a window: the lowest point of its host walls (mm); None without hosts."""
    hosts = [h for h in list(get_property(window, "Hosts", []) or []) if hasattr(h, "Shape")]
    boxes = [h.Shape.BoundBox for h in hosts if not h.Shape.isNull()]
    return min(b.ZMin for b in boxes) if boxes else None


def _frame(portal: Portal) -> Tuple[Any, Any, Any]:
    """(the sill corner, the horizontal edge, the upward edge) of a wall portal (its edge order
    follows the room's side, docs/workbench-daylight.md, so either edge may be the width)."""
    a, b = portal.edge1, portal.edge2
    width, height = (a, b) if abs(b.z) >= abs(a.z) else (b, a)
    if height.z < 0:
        return portal.corner + height, width, height * -1.0
    return portal.corner, width, height


def reference_point(portal: Portal, floor: Optional[float]) -> ReferencePoint:
    """The EN 17037 reference point of a window's portal: on the portal's plane (the wall's
    inner face), mid-width, at the opening's centre height raised to 1.2 m above the floor and
    0.3 m above the sill. Where the opening's top is not above that height, the point stays at
    the centre height and ``note`` says so (the standard's heights cannot be met in the
    opening: a point above its top would look at the wall, not out)."""
    low, width, height = _frame(portal)
    if height.z <= 0.0:
        raise ValueError("is not a vertical opening (no reference point on it)")
    sill, top = low.z, low.z + height.z
    centre = sill + 0.5 * height.z
    wanted = max(centre, sill + ABOVE_SILL_MM)
    if floor is not None:
        wanted = max(wanted, floor + ABOVE_FLOOR_MM)
    z, note = wanted, ""
    if wanted >= top:
        z = centre
        note = (f"its top, {(top - (floor if floor is not None else sill)) / 1000.0:.2f} m above "
                "the floor, is not above EN 17037's 1.2 m over the floor and 0.3 m over the "
                "sill: its reference point is at the opening's centre height")
    position = low + width * 0.5 + height * ((z - sill) / height.z)
    return ReferencePoint(portal.label, position, portal.inward * -1.0, note)


def assessment_date(sky: Any) -> str:
    """``SunlightDate``, or 21 March of the Sky's ``Date`` year when empty (ValueError naming
    the property when malformed)."""
    text = str(sky.SunlightDate).strip()
    try:
        if not text:
            year = datetime.date.fromisoformat(str(sky.Date).strip()).year
            return datetime.date(year, 3, 21).isoformat()
        return datetime.date.fromisoformat(text).isoformat()
    except ValueError:
        prop = "SunlightDate" if text else "Date"
        raise ValueError(f"Sky '{sky.Label}': {prop} must be YYYY-MM-DD, got "
                         f"{getattr(sky, prop)!r}") from None


def in_span(day: str) -> bool:
    """Whether ``day`` lies in EN 17037's 1 February ... 21 March."""
    date = datetime.date.fromisoformat(day)
    return SPAN[0] <= (date.month, date.day) <= SPAN[1]


def exposure(sky: Any, found: Found, site: Any) -> Tuple[Dict[str, Any], List[Tuple[str, str]]]:
    """The scene's ``sunlight_exposure`` for the Sky's window portals and (level, text)
    problems (ValueError for a bad date or no window)."""
    windows = {w.Name: w for w in found.windows}
    points, problems = [], []
    for portal in found.portals:
        window = windows.get(portal.source)
        if window is None:  # a selected face (a skylight): EN 17037 points are in windows
            continue
        point = reference_point(portal, floor_z(window))
        if point.note:
            problems.append(("warning", f"Sky '{sky.Label}': window '{window.Label}': "
                                        f"{point.note}"))
        points.append(point.scene_entry())
    if not points:
        raise ValueError(f"Sky '{sky.Label}': sunlight exposure needs a window among its "
                         "portals (EN 17037's points are on windows)")
    day = assessment_date(sky)
    if not in_span(day):
        problems.append(("warning", f"Sky '{sky.Label}': SunlightDate {day} is outside EN "
                                    "17037's 1 February ... 21 March"))
    entry = {"site": {"latitude_deg": site.latitude_deg, "longitude_deg": site.longitude_deg,
                      "utc_offset_h": site.utc_offset_h, "elevation_m": site.elevation_m},
             "date": day, "min_elevation_deg": float(sky.SunlightMinAltitude),
             "step_minutes": int(sky.SunlightStepMinutes), "points": points}
    return entry, problems
