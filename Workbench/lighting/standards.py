# SPDX-License-Identifier: LGPL-2.1-or-later
"""EN 12464-1 calculation-grid rules and surface requirements (pure Python, no FreeCAD needed)."""
from __future__ import annotations

import math
from typing import NamedTuple, Optional, Tuple

#: Height of the horizontal work plane for task areas.
WORKPLANE_HEIGHT_M = 0.80
#: Band along the walls left out of a room's calculation grid.
WALL_BAND_M = 0.50
#: Largest grid spacing the rule allows.
MAX_SPACING_M = 10.0


def grid_spacing_m(longer_side_m: float) -> float:
    """Maximum grid spacing p = 0.2 * 5^log10(d) m for an area whose longer side is d metres
    (EN 12464-1), capped at 10 m. d = 5 m gives p = 0.61 m, d = 10 m gives 1.0 m."""
    if longer_side_m <= 0.0:
        raise ValueError(f"grid area side must be > 0 m (got {longer_side_m})")
    return min(0.2 * 5.0 ** math.log10(longer_side_m), MAX_SPACING_M)


def grid_cells(length_u_m: float, length_v_m: float, spacing_m: float = 0.0) -> Tuple[int, int, float]:
    """Number of grid cells along u and v, and the spacing used.

    ``spacing_m`` <= 0 selects the EN 12464-1 spacing from the longer side; the same spacing
    applies to both sides, n = ceil(side / p) (at least 1).
    """
    if length_u_m <= 0.0 or length_v_m <= 0.0:
        raise ValueError(f"grid area must have positive sides (got {length_u_m} x {length_v_m} m)")
    p = spacing_m if spacing_m > 0.0 else grid_spacing_m(max(length_u_m, length_v_m))
    # A tiny tolerance keeps 4.0 m / 0.5 m at 8 cells despite floating-point noise.
    nu = max(1, math.ceil(length_u_m / p - 1e-9))
    nv = max(1, math.ceil(length_v_m / p - 1e-9))
    return nu, nv, p


# -- Calculation surfaces and their requirements (EN 12464-1:2021) ---------------------------
#: What a grid measures: the horizontal work plane (task area), a wall, a ceiling or a floor.
SURFACE_KINDS = ("Work plane", "Wall", "Ceiling", "Floor")
#: Border band left out of a new grid by kind: the 0.5 m band along the walls for task areas
#: and floors; walls and ceilings are evaluated over the whole surface.
BORDER_BAND_M = {"Work plane": WALL_BAND_M, "Floor": WALL_BAND_M, "Wall": 0.0, "Ceiling": 0.0}
#: Distance of a wall, ceiling or floor grid in front of its surface (toward the room): the
#: solver counts grids lying on a surface correctly, the centimetre keeps the cells clear of
#: the surface in the 3D view and of float ties.
SURFACE_OFFSET_M = 0.01

#: "Custom" leaves a grid's RequiredLux and RequiredUniformity as typed.
CUSTOM = "Custom"


class Requirement(NamedTuple):
    """Maintained illuminance Em (lx) and uniformity U0 required on one kind of surface."""

    lux: float
    uniformity: float


# Rows of EN 12464-1:2021 as quoted by luminaire makers (verify against
# the standard before relying on one): task area Em and U0, walls and ceiling Em with U0 >= 0.10.
# "General" is the standard's minimum for walls (75 lx) and ceilings (50 lx) in any interior;
# offices, conference rooms and drawing offices ask 150 lx on walls and 100 lx on the ceiling.
# A floor grid is judged like the task area (corridors are evaluated at floor level).
_WALL_U0 = 0.10
_ROWS = {
    # activity: (task Em, task U0, wall Em, ceiling Em)
    "General": (0.0, 0.0, 75.0, 50.0),
    "Office: writing, typing, reading, data processing": (500.0, 0.60, 150.0, 100.0),
    "Office: filing, copying": (300.0, 0.40, 150.0, 100.0),
    "Conference and meeting rooms": (500.0, 0.60, 150.0, 100.0),
    "Technical drawing": (750.0, 0.70, 150.0, 100.0),
    "Corridors and circulation areas": (100.0, 0.40, 75.0, 50.0),
}
#: The presets a grid's ``Activity`` offers, "Custom" first.
ACTIVITIES = (CUSTOM,) + tuple(_ROWS)


def requirement(activity: str, surface: str) -> Optional[Requirement]:
    """The EN 12464-1 requirement of ``surface`` (one of SURFACE_KINDS) in ``activity`` (one of
    ACTIVITIES); None for "Custom". Raises ValueError naming an unknown activity or surface."""
    if surface not in SURFACE_KINDS:
        raise ValueError(f"unknown surface kind {surface!r}; one of {SURFACE_KINDS}")
    if activity == CUSTOM:
        return None
    if activity not in _ROWS:
        raise ValueError(f"unknown activity {activity!r}; one of {ACTIVITIES}")
    task_lux, task_u0, wall_lux, ceiling_lux = _ROWS[activity]
    if surface == "Wall":
        return Requirement(wall_lux, _WALL_U0)
    if surface == "Ceiling":
        return Requirement(ceiling_lux, _WALL_U0)
    return Requirement(task_lux, task_u0)


def surface_kind(normal_z: float) -> str:
    """The kind of a grid on a planar face whose room-side unit normal has this z component:
    faces looking up carry a work plane, faces looking down are ceilings, the rest walls
    (more than 45 degrees from the vertical)."""
    if normal_z > 0.7071:
        return "Work plane"
    if normal_z < -0.7071:
        return "Ceiling"
    return "Wall"
