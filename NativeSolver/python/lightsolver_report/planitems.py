# SPDX-License-Identifier: LGPL-2.1-or-later
"""What a plan marks besides the building: luminaires (position, outline, aiming), calculation
grids and surfaces, observers and observer grids, read from the scene (docs/scene-format.md)
and named by the labels the user gave (``metadata.labels``). Plain geometry, no drawing."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from lightsolver_report.meshes import Mesh
from lightsolver_report.section import Level, drawn_edges

#: A luminaire whose beam axis leans more than this from straight down gets an aiming arrow.
AIMED_DEG = 2.0
#: How each luminaire type is named in the plan's table.
TYPE_NAMES = {"point": "point source", "spot": "spot", "area": "area source",
              "directional": "parallel beam", "photometric": "photometric"}


def _vec(value: Any, default: Sequence[float] = (0.0, 0.0, 0.0)) -> np.ndarray:
    """A finite 3-vector from the scene, else ``default``."""
    try:
        out = np.asarray(value, dtype=np.float64).reshape(3)
    except (TypeError, ValueError):
        return np.asarray(default, dtype=np.float64)
    return out if np.all(np.isfinite(out)) else np.asarray(default, dtype=np.float64)


def _unit(v: np.ndarray) -> Optional[np.ndarray]:
    length = float(np.linalg.norm(v))
    return v / length if length > 1e-12 and math.isfinite(length) else None


@dataclass
class LuminaireMark:
    """A luminaire in plan: its centre, its outline (area and beam openings) and its beam axis
    (None: a point source, which has none)."""

    number: int
    name: str
    label: str
    type: str
    position: np.ndarray
    outline: Optional[np.ndarray] = None  # (4, 3) parallelogram
    aim: Optional[np.ndarray] = None  # unit vector
    rotation_deg: float = 0.0

    @property
    def type_name(self) -> str:
        return TYPE_NAMES.get(self.type, self.type)

    @property
    def tilt_deg(self) -> Optional[float]:
        """The beam axis' angle from straight down (0: aimed down), None without an axis."""
        if self.aim is None:
            return None
        return math.degrees(math.acos(max(-1.0, min(1.0, -float(self.aim[2])))))

    @property
    def aimed(self) -> bool:
        """Aimed away from straight down (the plan draws its aiming arrow)."""
        tilt = self.tilt_deg
        return tilt is not None and tilt > AIMED_DEG

    def aiming_point(self, floor_z: float) -> Optional[np.ndarray]:
        """Where the beam axis meets the floor, None if it does not point down to it."""
        if self.aim is None or self.aim[2] > -0.02 or self.position[2] <= floor_z:
            return None
        t = (floor_z - self.position[2]) / self.aim[2]
        return self.position + t * self.aim


@dataclass
class GridMark:
    """A calculation grid (or an observer grid's rectangle): its four corners."""

    name: str
    label: str
    corners: np.ndarray  # (4, 3): corner, +edge1, +edge1+edge2, +edge2
    cells: Tuple[int, int]

    @property
    def z(self) -> float:
        return float(self.corners[:, 2].mean())

    @property
    def horizontal(self) -> bool:
        return float(np.ptp(self.corners[:, 2])) < 1e-6


@dataclass
class SurfaceMark:
    """A surface target: its outline edges (the mesh's free edges and creases)."""

    name: str
    label: str
    mesh: str
    edges: np.ndarray  # (e, 2, 3)
    centre: np.ndarray
    horizontal: bool


@dataclass
class ObserverMark:
    """An observer (one eye) or an observer grid (its eyes and lines of sight)."""

    name: str
    label: str
    positions: np.ndarray  # (p, 3)
    directions: np.ndarray  # (d, 3) unit vectors
    grid: bool = False

    @property
    def z(self) -> float:
        return float(self.positions[:, 2].min())


@dataclass
class PlanItems:
    """Everything the plans mark, for the whole scene."""

    luminaires: List[LuminaireMark] = field(default_factory=list)
    grids: List[GridMark] = field(default_factory=list)
    surfaces: List[SurfaceMark] = field(default_factory=list)
    observers: List[ObserverMark] = field(default_factory=list)

    def on(self, level: Level) -> "PlanItems":
        """The items of one storey."""
        return PlanItems(
            [m for m in self.luminaires if level.holds(float(m.position[2]))],
            [g for g in self.grids if level.holds(g.z)],
            [s for s in self.surfaces if level.holds(float(s.centre[2]))],
            [o for o in self.observers if level.holds(o.z)])

    def points(self) -> np.ndarray:
        """Every point the plan must show (for its extent), shape (n, 3)."""
        pts = [m.position[None] for m in self.luminaires]
        pts += [m.outline for m in self.luminaires if m.outline is not None]
        pts += [g.corners for g in self.grids] + [o.positions for o in self.observers]
        pts += [s.edges.reshape(-1, 3) for s in self.surfaces if len(s.edges)]
        return np.concatenate(pts) if pts else np.zeros((0, 3))


def _luminaire(number: int, lum: Dict[str, Any], label: str) -> LuminaireMark:
    kind = str(lum.get("type", ""))
    mark = LuminaireMark(number, str(lum.get("name", "")), label, kind, np.zeros(3))
    if kind in ("area", "directional"):
        corner, e1, e2 = (_vec(lum.get(k)) for k in ("corner", "edge1", "edge2"))
        mark.outline = np.stack([corner, corner + e1, corner + e1 + e2, corner + e2])
        mark.position = corner + 0.5 * (e1 + e2)
        mark.aim = _unit(np.cross(e1, e2) if kind == "area" else _vec(lum.get("direction")))
    else:
        mark.position = _vec(lum.get("position"))
        if kind == "spot":
            mark.aim = _unit(_vec(lum.get("direction"), (0.0, 0.0, -1.0)))
        elif kind == "photometric":
            mark.aim = _unit(_vec(lum.get("aim", (0.0, 0.0, -1.0)), (0.0, 0.0, -1.0)))
            rotation = lum.get("rotation_deg", 0.0)
            mark.rotation_deg = float(rotation) if isinstance(rotation, (int, float)) else 0.0
    return mark


def _grid(target: Dict[str, Any], label: str) -> GridMark:
    corner, e1, e2 = (_vec(target.get(k)) for k in ("corner", "edge1", "edge2"))
    cells = target.get("cells") or (1, 1)
    try:
        nu, nv = int(cells[0]), int(cells[1])
    except (TypeError, ValueError, IndexError):
        nu, nv = 1, 1
    return GridMark(str(target.get("name", "")), label,
                    np.stack([corner, corner + e1, corner + e1 + e2, corner + e2]), (nu, nv))


def _observer(target: Dict[str, Any], label: str) -> Optional[ObserverMark]:
    name = str(target.get("name", ""))
    up = _unit(_vec(target.get("up", (0.0, 0.0, 1.0)), (0.0, 0.0, 1.0)))
    if target.get("type") == "observer":
        view = _unit(_vec(target.get("view_direction")))
        return ObserverMark(name, label, _vec(target.get("position"))[None],
                            np.zeros((0, 3)) if view is None else view[None])
    if "positions" in target:
        positions = np.asarray([_vec(p) for p in target.get("positions") or []]).reshape(-1, 3)
    else:
        grid = _grid(target, label)
        nu, nv = grid.cells
        e1, e2 = grid.corners[1] - grid.corners[0], grid.corners[3] - grid.corners[0]
        u, v = np.meshgrid((np.arange(nu) + 0.5) / nu, (np.arange(nv) + 0.5) / nv)
        positions = (grid.corners[0] + u.reshape(-1, 1) * e1 + v.reshape(-1, 1) * e2)
    if "view_directions" in target:
        dirs = [_unit(_vec(d)) for d in target.get("view_directions") or []]
    else:
        step = target.get("view_step_deg")
        dirs = _turns(float(step), up) if isinstance(step, (int, float)) and step > 0 else []
    directions = np.asarray([d for d in dirs if d is not None]).reshape(-1, 3)
    if not len(positions):
        return None
    return ObserverMark(name, label, positions, directions, grid=True)


def _turns(step_deg: float, up: Optional[np.ndarray]) -> List[np.ndarray]:
    """Lines of sight every ``step_deg`` about ``up``, starting at +x (docs/scene-format.md)."""
    up = up if up is not None else np.array([0.0, 0.0, 1.0])
    x = np.array([1.0, 0.0, 0.0]) - up * up[0]
    x = _unit(x) if _unit(x) is not None else _unit(np.array([0.0, 1.0, 0.0]) - up * up[1])
    y = np.cross(up, x)
    count = max(1, min(360, int(round(360.0 / step_deg))))
    return [math.cos(a) * x + math.sin(a) * y
            for a in (math.radians(step_deg * k) for k in range(count))]


def _surface(target: Dict[str, Any], label: str, meshes: Dict[str, Mesh]) -> Optional[SurfaceMark]:
    mesh = meshes.get(str(target.get("mesh", "")))
    if mesh is None or not len(mesh.triangles):
        return None
    corners = mesh.corners
    edges = drawn_edges(corners)
    horizontal = bool(np.ptp(corners[:, :, 2]) < 0.05 * max(1e-9, float(np.ptp(
        corners[:, :, :2].reshape(-1, 2), axis=0).max())))
    return SurfaceMark(str(target.get("name", "")), label, mesh.name, edges,
                       corners.reshape(-1, 3).mean(axis=0), horizontal)


def plan_items(scene: Dict[str, Any], meshes: Sequence[Mesh],
               labels: Dict[str, str]) -> PlanItems:
    """The luminaires and targets of the scene as plan marks, named by their labels."""
    items = PlanItems()
    by_name = {m.name: m for m in meshes}
    for lum in scene.get("luminaires", []) or []:
        # Skies and suns have no place in the room (their openings are the windows drawn).
        if isinstance(lum, dict) and lum.get("type") not in ("sky", "sun"):
            name = str(lum.get("name", ""))
            items.luminaires.append(_luminaire(len(items.luminaires) + 1, lum,
                                               str(labels.get(name, name))))
    for target in scene.get("targets", []) or []:
        if not isinstance(target, dict):
            continue
        name = str(target.get("name", ""))
        label = str(labels.get(name, name))
        kind = target.get("type")
        if kind == "grid":
            items.grids.append(_grid(target, label))
        elif kind == "surface":
            mark = _surface(target, label, by_name)
            if mark is not None:
                items.surfaces.append(mark)
        elif kind in ("observer", "observer_grid"):
            mark = _observer(target, label)
            if mark is not None:
                items.observers.append(mark)
    return items


# --- what the plan's tables print ------------------------------------------------------------

COMPASS = ("north", "north-east", "east", "south-east", "south", "south-west", "west",
           "north-west")


def _coord(value: float) -> str:
    return f"{value + 0.0:.2f}"  # + 0.0: no "-0.00"


def direction_name(d: np.ndarray, north_deg: Optional[float] = None) -> str:
    """A direction in plan words: a compass point and bearing when north is known, else the
    model axis it runs along or its angle from +x; 'up' or 'down' when (nearly) vertical."""
    horizontal = math.hypot(float(d[0]), float(d[1]))
    if horizontal < 0.02 * max(1e-12, float(np.linalg.norm(d))):
        return "up" if d[2] > 0 else "down"
    phi = math.degrees(math.atan2(float(d[1]), float(d[0]))) % 360.0
    if north_deg is not None:
        bearing = (90.0 + north_deg - phi) % 360.0
        return f"{COMPASS[int(((bearing + 22.5) % 360.0) // 45.0)]} ({bearing:.0f}°)"
    for angle, axis in ((0, "+x"), (90, "+y"), (180, "−x"), (270, "−y"), (360, "+x")):
        if abs(phi - angle) < 0.5:
            return axis
    return f"{phi:.0f}° from +x"


@dataclass
class LuminaireRow:
    """One luminaire of a plan's position table (text as printed)."""

    number: int
    label: str
    type: str
    x: str
    y: str
    z: str
    height: str  # above the storey's floor
    aiming: str


def luminaire_row(mark: LuminaireMark, floor_z: float,
                  north_deg: Optional[float] = None) -> LuminaireRow:
    """The table row of a luminaire: centre, mounting height above the floor, aiming."""
    p = mark.position
    tilt = mark.tilt_deg
    if tilt is None:
        aiming = "– (all directions)"
    elif not mark.aimed:
        aiming = "straight down"
    else:
        point = mark.aiming_point(floor_z)
        aiming = (f"tilted {tilt:.0f}° to ({_coord(point[0])}, {_coord(point[1])}) on the "
                  "floor" if point is not None else
                  f"tilted {tilt:.0f}°, toward {direction_name(mark.aim, north_deg)}")
    if mark.type == "photometric" and abs(mark.rotation_deg) > 1e-9:
        aiming += f"; turned {mark.rotation_deg:g}°"
    return LuminaireRow(mark.number, mark.label, mark.type_name, _coord(p[0]), _coord(p[1]),
                        _coord(p[2]), _coord(p[2] - floor_z), aiming)


@dataclass
class ObserverRow:
    """One observer (or observer grid) of a plan's table (text as printed)."""

    label: str
    eyes: str
    height: str  # the eyes above the storey's floor
    views: str


def observer_row(mark: ObserverMark, floor_z: float,
                 north_deg: Optional[float] = None) -> ObserverRow:
    """Where the eyes are and where they look."""
    heights = sorted({round(float(z) - floor_z, 2) for z in mark.positions[:, 2]})
    height = ", ".join(_coord(h) for h in heights[:4]) + (" …" if len(heights) > 4 else "")
    if len(mark.positions) == 1:
        p = mark.positions[0]
        eyes = f"({_coord(p[0])}, {_coord(p[1])}, {_coord(p[2])})"
    else:
        eyes = f"{len(mark.positions)} positions"
    names = [direction_name(d, north_deg) for d in mark.directions]
    if len(names) > 4:
        views = f"{len(names)} directions"
    else:
        views = ", ".join(names) if names else "–"
    return ObserverRow(mark.label, eyes, height, views)
