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


#: The requirements table shipped as data (Resources/requirements/en12464-1.json), the one the
#: solver reads for a target's "task": the presets come from it, not from code.
TABLE_PARTS = ("requirements", "en12464-1.json")
#: Preset of walls and ceilings in any interior (no task area).
GENERAL = "General (walls and ceilings of any interior)"


class Task(NamedTuple):
    """One row of the table: what a preset fills in."""

    id: str
    name: str
    area: str
    task: Requirement
    wall: Requirement
    ceiling: Requirement
    ugr_limit: Optional[float]


def _load_table() -> Tuple[dict, Tuple[Task, ...]]:
    """The table's document and its rows (ValueError naming the file when it is unreadable)."""
    import json

    from lighting import resources

    path = resources.find(*TABLE_PARTS)
    if path is None:
        raise ValueError(f"the requirements table Resources/{'/'.join(TABLE_PARTS)} was not found "
                         f"(looked in {', '.join(resources.candidates(*TABLE_PARTS))})")
    try:
        with open(path, encoding="utf-8") as stream:
            doc = json.load(stream)
        u0 = float(doc["walls_and_ceilings"]["u0"])
        rows = tuple(Task(r["id"], f"{r['area'].capitalize()}: {r['name']}", r["area"],
                          Requirement(float(r["em_lux"]), float(r["u0"])),
                          Requirement(float(r["wall_em_lux"]), u0),
                          Requirement(float(r["ceiling_em_lux"]), u0), r.get("ugr_l"))
                     for r in doc["tasks"])
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise ValueError(f"{path}: not a readable requirements table ({exc})") from exc
    return doc, rows


_DOC, TASKS = _load_table()
_WC = _DOC["walls_and_ceilings"]
_GENERAL = Task("", GENERAL, "", Requirement(0.0, 0.0),
                Requirement(float(_WC["general_wall_em_lux"]), float(_WC["u0"])),
                Requirement(float(_WC["general_ceiling_em_lux"]), float(_WC["u0"])), None)
_BY_NAME = {t.name: t for t in (_GENERAL,) + TASKS}
#: Where the figures come from (for reports and tooltips).
SOURCE = str(_DOC.get("source", ""))
#: The presets a grid's ``Activity`` offers: "Custom" first, then the general wall/ceiling
#: minimum, then the table's task areas.
ACTIVITIES = (CUSTOM,) + tuple(_BY_NAME)


def task_of(activity: str) -> Optional[Task]:
    """The table row of a preset name (None for Custom and General)."""
    row = _BY_NAME.get(activity)
    return row if row is not None and row.id else None


def requirement(activity: str, surface: str) -> Optional[Requirement]:
    """The EN 12464-1 requirement of ``surface`` (one of SURFACE_KINDS) in ``activity`` (one of
    ACTIVITIES); None for "Custom". A floor grid is judged like the task area (corridors are
    evaluated at floor level). Raises ValueError naming an unknown activity or surface."""
    if surface not in SURFACE_KINDS:
        raise ValueError(f"unknown surface kind {surface!r}; one of {SURFACE_KINDS}")
    if activity == CUSTOM:
        return None
    row = _BY_NAME.get(activity)
    if row is None:
        raise ValueError(f"unknown activity {activity!r}; one of {ACTIVITIES}")
    if surface == "Wall":
        return row.wall
    if surface == "Ceiling":
        return row.ceiling
    return row.task


def surface_kind(normal_z: float) -> str:
    """The kind of a grid on a planar face whose room-side unit normal has this z component:
    faces looking up carry a work plane, faces looking down are ceilings, the rest walls
    (more than 45 degrees from the vertical)."""
    if normal_z > 0.7071:
        return "Work plane"
    if normal_z < -0.7071:
        return "Ceiling"
    return "Wall"
