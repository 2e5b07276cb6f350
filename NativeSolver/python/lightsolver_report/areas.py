# SPDX-License-Identifier: LGPL-2.1-or-later
"""A calculation area (a results target) as the report shows it: its statistics with their
intervals, requirements, verdicts and, for an eye (observer, observer grid), its UGR, position
and line of sight. Plain data, no HTML: the templates lay it out."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from lightsolver_report.daylight import DaylightFactor, read_daylight_factor
from lightsolver_report.fmt import finite
from lightsolver_results import Stat, Target

#: Verdict keys in the order the report lists them, with the requirement key and unit of each.
QUANTITIES: Tuple[Tuple[str, str, str], ...] = (
    ("em", "em_lux", "lx"), ("emin", "emin_lux", "lx"), ("u0", "u0", ""), ("ud", "ud", ""))

#: Daylight-factor verdicts (docs/scene-format.md, "Results"): key, requirement key, in print order.
DF_QUANTITIES: Tuple[Tuple[str, str], ...] = (("df_target", "df_target_percent"),
                                              ("df_minimum", "df_minimum_percent"))

Vec = Tuple[float, float, float]


@dataclass
class Verdict:
    """One requirement's verdict, as the solver decided it from the interval."""

    key: str  # em, emin, u0, ud, ugr
    verdict: str  # pass, fail, undecided
    value: Optional[float]
    low: Optional[float]
    high: Optional[float]
    required: Optional[float]
    relation: str = ">="
    to_decide_photons: Optional[float] = None
    to_decide_seconds: Optional[float] = None

    @property
    def is_lux(self) -> bool:
        return self.key in ("em", "emin")

    @property
    def is_df(self) -> bool:
        return self.key.startswith("df_")


@dataclass
class Requirement:
    """One stated requirement (from the results' resolved ``requirements``)."""

    key: str  # em, emin, u0, ud, ugr
    relation: str
    value: float


@dataclass
class GridData:
    """A grid's cells (lux, shape (nv, nu), row iv along edge2) and how to draw them."""

    lux: np.ndarray
    size_u_m: float
    size_v_m: float
    origin_u_m: float = 0.0
    origin_v_m: float = 0.0
    axis_u: str = "u"
    axis_v: str = "v"


@dataclass
class Area:
    """A calculation area (a target) with its statistics, requirements and verdicts."""

    name: str
    label: str
    type: str
    area_m2: Optional[float]
    hits: Optional[int]
    em: Stat
    emin: Optional[Stat] = None
    emax: Optional[Stat] = None
    u0: Optional[Stat] = None
    ud: Optional[Stat] = None
    cells_uv: Optional[Tuple[int, int]] = None
    requirements: List[Requirement] = field(default_factory=list)
    task: Optional[str] = None
    source: Optional[str] = None
    verdict: Optional[str] = None
    verdicts: List[Verdict] = field(default_factory=list)
    grid: Optional[GridData] = None
    #: Observers (eyes for discomfort glare): the UGR with its interval; an observer grid's
    #: maximum over its points, the interval simultaneous over them.
    ugr: Optional[Stat] = None
    #: Background luminance L_b (cd/m²) at the eye (an observer grid: at its maximum).
    background: Optional[Stat] = None
    #: An observer's eye and line of sight.
    position: Optional[Vec] = None
    view: Optional[Vec] = None
    #: Observer grids: positions, view directions, each point's UGR [position][direction]
    #: (None: no glare or unbounded) and where the maximum is.
    observer_positions: List[Vec] = field(default_factory=list)
    observer_directions: List[Vec] = field(default_factory=list)
    observer_ugr: List[List[Optional[float]]] = field(default_factory=list)
    max_at: Optional[Tuple[Vec, Vec]] = None
    horizontal: bool = False
    power_density_w_m2: Optional[float] = None
    power_density_w_m2_100lx: Optional[float] = None
    plan_svg: str = ""
    chart_svg: str = ""
    chart_note: str = ""
    #: A daylight-factor grid's DF (its page in the daylight section), None otherwise.
    daylight: Optional[DaylightFactor] = None

    @property
    def is_glare(self) -> bool:
        return self.type in ("observer", "observer_grid")

    @property
    def ugr_name(self) -> str:
        return "max UGR" if self.type == "observer_grid" else "UGR"

    @property
    def ugr_verdict(self) -> Optional[Verdict]:
        return next((v for v in self.verdicts if v.key == "ugr"), None)

    @property
    def ugr_limit(self) -> Optional[float]:
        return next((r.value for r in self.requirements if r.key == "ugr"), None)

    @property
    def undecided(self) -> List[Verdict]:
        return [v for v in self.verdicts if v.verdict == "undecided"]

    @property
    def to_decide(self) -> Optional[Verdict]:
        """The undecided verdict that needs the most photons (with an estimate), or None."""
        known = [v for v in self.undecided if v.to_decide_photons is not None]
        return max(known, key=lambda v: v.to_decide_photons) if known else None

    @property
    def point_maxima(self) -> List[Tuple[Vec, Optional[float], Optional[Vec]]]:
        """An observer grid's positions with the largest UGR over its lines of sight and the
        line of sight it is seen in (None: no glare there), for grids with too many lines of
        sight for one column each."""
        out = []
        for position, row in zip(self.observer_positions, self.observer_ugr):
            known = [(u, d) for u, d in zip(row, self.observer_directions) if u is not None]
            top = max(known, key=lambda ud: ud[0]) if known else (None, None)
            out.append((position, top[0], top[1]))
        return out

    @property
    def stats(self) -> List[Tuple[str, Stat]]:
        """(key, statistic) of the illuminance statistics this area has, in print order."""
        found = [("em", self.em), ("emin", self.emin), ("emax", self.emax), ("u0", self.u0),
                 ("ud", self.ud)]
        return [(k, s) for k, s in found if s is not None]


def _requirements(req: Optional[Dict[str, Any]]) -> List[Requirement]:
    if not isinstance(req, dict):
        return []
    items = [Requirement(key, ">=", float(req[rkey])) for key, rkey, _ in QUANTITIES
             if finite(req.get(rkey)) is not None]
    if finite(req.get("ugr_max")) is not None:
        items.append(Requirement("ugr", "<=", float(req["ugr_max"])))
    items += [Requirement(key, ">=", float(req[rkey])) for key, rkey in DF_QUANTITIES
              if finite(req.get(rkey)) is not None]
    return items


def _verdicts(raw: Any) -> List[Verdict]:
    if not isinstance(raw, dict):
        return []
    found = []
    known = [k for k, _, _ in QUANTITIES] + [k for k, _ in DF_QUANTITIES]
    for key in known + sorted(set(raw) - set(known)):
        v = raw.get(key)
        if not isinstance(v, dict):
            continue
        decide = v.get("to_decide") if isinstance(v.get("to_decide"), dict) else {}
        found.append(Verdict(key, str(v.get("verdict", "undecided")), finite(v.get("value")),
                             finite(v.get("ci_low")), finite(v.get("ci_high")),
                             finite(v.get("required")), str(v.get("relation", ">=")),
                             finite(decide.get("photons")), finite(decide.get("seconds"))))
    return found


def _axis_name(edge: np.ndarray) -> Optional[int]:
    """The world axis (0, 1, 2) an edge runs along in the positive sense, else None."""
    length = float(np.linalg.norm(edge))
    for axis in range(3):
        if length > 0 and edge[axis] > 0 and abs(edge[axis] - length) <= 1e-9 * length:
            return axis
    return None


def _grid_data(target: Target, scene_target: Dict[str, Any]) -> Optional[GridData]:
    nu, nv = target.cells_uv or (0, 0)
    cells = target.cells
    if nu * nv == 0 or len(cells) != nu * nv:
        return None
    lux = np.array([float(c["lux"]) for c in cells], dtype=float).reshape(nv, nu)
    e1 = np.asarray(scene_target.get("edge1", (1.0, 0.0, 0.0)), dtype=float)
    e2 = np.asarray(scene_target.get("edge2", (0.0, 1.0, 0.0)), dtype=float)
    corner = np.asarray(scene_target.get("corner", (0.0, 0.0, 0.0)), dtype=float)
    grid = GridData(lux, float(np.linalg.norm(e1)), float(np.linalg.norm(e2)))
    a1, a2 = _axis_name(e1), _axis_name(e2)
    if a1 is not None and a2 is not None and a1 != a2:  # axis-parallel: world coordinates
        grid.origin_u_m, grid.origin_v_m = float(corner[a1]), float(corner[a2])
        grid.axis_u, grid.axis_v = "xyz"[a1], "xyz"[a2]
    return grid


def _is_horizontal_up(scene_target: Dict[str, Any]) -> bool:
    e1 = np.asarray(scene_target.get("edge1", (1.0, 0.0, 0.0)), dtype=float)
    e2 = np.asarray(scene_target.get("edge2", (0.0, 1.0, 0.0)), dtype=float)
    n = np.cross(e1, e2)
    norm = float(np.linalg.norm(n))
    return norm > 0 and n[2] / norm > 0.999


def _vec(value: Any) -> Optional[Vec]:
    try:
        x, y, z = (float(c) for c in value)
    except (TypeError, ValueError):
        return None
    return (x, y, z) if all(math.isfinite(c) for c in (x, y, z)) else None


def _glare(area: Area, target: Target, scene_target: Dict[str, Any]) -> None:
    entry = target.entry
    area.ugr = target.ugr
    area.background = Stat(finite(entry.get("background_luminance_cd_m2")),
                           finite(entry.get("background_ci_low_cd_m2")),
                           finite(entry.get("background_ci_high_cd_m2")))
    if target.type == "observer":
        area.position = _vec(scene_target.get("position"))
        area.view = _vec(scene_target.get("view_direction"))
    grid = target.observer_grid
    if grid is not None:
        area.observer_positions = [tuple(p) for p in grid.positions]
        area.observer_directions = [tuple(d) for d in grid.view_directions]
        area.observer_ugr = [list(row) for row in grid.ugr]
        if grid.max_at is not None:
            area.max_at = (grid.max_position, grid.max_direction)


def build_area(target: Target, scene_target: Dict[str, Any], labels: Dict[str, str]) -> Area:
    """One calculation area from its results target (lightsolver_results' per-type reading)
    and its scene entry."""
    area = Area(name=target.name, label=labels.get(target.name, target.name), type=target.type,
                area_m2=target.area_m2, hits=target.hits, em=target.em)
    if target.is_grid:
        area.emin, area.emax, area.u0 = target.emin, target.emax, target.u0
        area.ud = target.ud
        area.cells_uv = target.cells_uv
        area.grid = _grid_data(target, scene_target)
        area.horizontal = _is_horizontal_up(scene_target)
    if target.is_glare:
        _glare(area, target, scene_target)
    req: Optional[Dict[str, Any]] = target.requirements or None
    if req is None:  # a solver that does not resolve them: show what the scene states
        req = scene_target.get("requirements")
    area.requirements = _requirements(req)
    if isinstance(req, dict):
        area.task = str(req["task"]) if req.get("task") else scene_target.get("task")
        area.source = str(req["source"]) if req.get("source") else None
    if target.is_grid and (scene_target.get("quantity") == "daylight_factor"
                           or "daylight_factor" in target.entry):
        area.daylight = read_daylight_factor(target.entry.get("daylight_factor"), req,
                                             area.cells_uv, labels,
                                             scene_target.get("requirements"))
    area.verdicts = _verdicts(target.entry.get("verdicts"))
    verdict = target.entry.get("verdict")
    area.verdict = str(verdict) if isinstance(verdict, str) else None
    return area
