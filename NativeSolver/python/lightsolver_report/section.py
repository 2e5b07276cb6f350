# SPDX-License-Identifier: LGPL-2.1-or-later
"""Plan geometry from the scene's triangles (numpy only, no drawing): the storeys (levels) of a
model, a horizontal section through a level (the cut walls as polylines and closed outlines),
and the top view of what lies below the section (triangles projected on the floor, with the
edges a drawing shows: outlines and creases, not the seams between coplanar triangles)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, Iterable, List, Optional, Sequence, Tuple

import numpy as np

from lightsolver_report.meshes import Mesh

#: Section height above the floor, as in architectural plans (walls, windows and doors cut,
#: tables and desks seen from above).
CUT_HEIGHT_M = 1.0
#: Coordinates closer than this are one point when chaining cut segments.
WELD_M = 1e-5
#: Two adjacent faces whose normals differ by more than this angle meet at a drawn edge.
CREASE_DEG = 25.0
#: A cut mesh reaching this share of the highest cut mesh's height above the floor is a wall.
WALL_SHARE = 0.9
#: A closed cut outline whose area over perimeter is below this is a wall's or a column's (when
#: the faces' normals do not tell).
THIN_M = 0.3
#: At most this many triangles of one mesh are drawn in the top view (the largest).
TOP_VIEW_MAX = 100000
#: Floors of two calculation grids closer than this belong to one storey.
STOREY_MIN_M = 1.5


@dataclass
class Level:
    """A storey: its floor, the section height, the next storey's floor (inf: none) and where
    what belongs to it starts (the lowest storey: everything below it too)."""

    floor_z: float
    cut_z: float
    top_z: float = math.inf
    bottom_z: float = -math.inf

    def holds(self, z: float) -> bool:
        """Whether a point at height ``z`` belongs to this storey."""
        return self.bottom_z - 0.1 <= z < self.top_z - 0.1


@dataclass
class Polyline:
    """A chain of cut segments: closed (a loop around a solid) or open (a cut sheet)."""

    points: np.ndarray  # (n, 2)
    closed: bool
    #: The cut segments it was chained from (k, 2, 2) and the plan direction (k, 2) of the
    #: normal of each one's triangle (zero when not known).
    segments: np.ndarray = field(default_factory=lambda: np.zeros((0, 2, 2)))
    normals: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))


@dataclass
class Layer:
    """One mesh's triangles below the section, projected: painted in order of height."""

    mesh: Mesh
    triangles: np.ndarray  # (k, 3, 2) projected corners, lowest first
    heights: np.ndarray  # (k,) each triangle's highest z
    edges: np.ndarray  # (e, 2, 2) projected drawn edges
    top_z: float
    #: Each edge's height (its higher end): edges and faces are painted together by height,
    #: so a face above an edge (a table's top over its legs) hides it.
    edge_heights: np.ndarray = field(default_factory=lambda: np.zeros(0))


@dataclass
class Section:
    """A level's plan geometry."""

    level: Level
    walls: List[Polyline] = field(default_factory=list)  # opaque, full height: walls
    furniture: List[Polyline] = field(default_factory=list)  # opaque, lower: cabinets, frames
    glass: List[Polyline] = field(default_factory=list)  # glass cut (windows)
    layers: List[Layer] = field(default_factory=list)  # top view below the cut, lowest first
    #: The meshes cut as walls (what bounds a room: floorarea.py).
    wall_meshes: List[Mesh] = field(default_factory=list)

    def bounds(self) -> Optional[Tuple[float, float, float, float]]:
        """(xmin, xmax, ymin, ymax) of the cut, None when nothing is cut."""
        pts = [p.points for p in self.walls + self.furniture + self.glass]
        if not pts:
            return None
        allp = np.concatenate(pts)
        return (float(allp[:, 0].min()), float(allp[:, 0].max()),
                float(allp[:, 1].min()), float(allp[:, 1].max()))


# --- triangles ------------------------------------------------------------------------------

def unit_normals(corners: np.ndarray) -> np.ndarray:
    """Unit normals (m, 3) of triangles (m, 3, 3) by their winding (zero for a degenerate)."""
    n = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return np.divide(n, length, out=np.zeros_like(n), where=length > 0)


def areas(corners: np.ndarray) -> np.ndarray:
    """Triangle areas (m,)."""
    return 0.5 * np.linalg.norm(
        np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)


def cut_segments(corners: np.ndarray, z: float) -> Tuple[np.ndarray, np.ndarray]:
    """Segments (k, 2, 2) in x, y where the plane at height ``z`` cuts the triangles (m, 3, 3),
    and the x, y part of each cut triangle's unit normal (k, 2). A corner exactly at ``z`` is
    taken as just above it (pick ``z`` with :func:`clear_height` to avoid such cases)."""
    if not len(corners):
        return np.zeros((0, 2, 2)), np.zeros((0, 2))
    d = corners[:, :, 2] - z
    above = d >= 0
    crossing = np.any(above, axis=1) & ~np.all(above, axis=1)
    c, d, above = corners[crossing], d[crossing], above[crossing]
    points, cuts = [], []
    for i, j in ((0, 1), (1, 2), (2, 0)):
        t = d[:, i] / np.where(d[:, i] == d[:, j], 1.0, d[:, i] - d[:, j])
        points.append(c[:, i, :2] + t[:, None] * (c[:, j, :2] - c[:, i, :2]))
        cuts.append(above[:, i] != above[:, j])
    points, cuts = np.stack(points, axis=1), np.stack(cuts, axis=1)
    order = np.argsort(~cuts, axis=1, kind="stable")[:, :2]  # the two cut edges
    return (np.take_along_axis(points, order[:, :, None], axis=1),
            unit_normals(c)[:, :2])


def clear_height(corners: np.ndarray, z: float, step: float = 0.0125) -> float:
    """``z``, moved up in small steps while some corner lies (almost) on it, so that no
    horizontal face or vertex sits in the section plane."""
    heights = corners[:, :, 2].ravel() if len(corners) else np.zeros(0)
    for _ in range(16):
        if not np.any(np.abs(heights - z) < 1e-4):
            break
        z += step
    return z


def chain(segments: np.ndarray, normals: Optional[np.ndarray] = None,
          weld: float = WELD_M) -> List[Polyline]:
    """Join segments that share end points into polylines; a chain that returns to its start
    is closed. Junctions of three or more segments end the chains that meet there.
    ``normals`` (k, 2), one per segment, go with each polyline's segments."""
    if not len(segments):
        return []
    if normals is None:
        normals = np.zeros((len(segments), 2))
    keys = np.round(segments / weld).astype(np.int64)
    keep = np.any(keys[:, 0] != keys[:, 1], axis=1)
    segments, keys, normals = segments[keep], keys[keep], normals[keep]
    ends: Dict[Tuple[int, int], List[Tuple[int, int]]] = {}
    for s in range(len(segments)):
        for e in (0, 1):
            ends.setdefault((int(keys[s, e, 0]), int(keys[s, e, 1])), []).append((s, e))
    used = np.zeros(len(segments), dtype=bool)

    def walk(s: int, e: int) -> List[int]:
        """Segment ends from (s, e) onward: the point at the far end, repeatedly."""
        path = []
        while True:
            far = 1 - e
            key = (int(keys[s, far, 0]), int(keys[s, far, 1]))
            path.append((s, far))
            nxt = [(t, f) for t, f in ends[key] if t != s and not used[t]]
            if len(ends[key]) != 2 or not nxt:
                return path
            s, e = nxt[0]
            used[s] = True

    lines = []
    for s in range(len(segments)):
        if used[s]:
            continue
        used[s] = True
        forward = walk(s, 0)
        start = (int(keys[s, 0, 0]), int(keys[s, 0, 1]))
        last = forward[-1]
        closed = (int(keys[last[0], last[1], 0]), int(keys[last[0], last[1], 1])) == start
        backward = [] if closed else walk(s, 1)
        # backward ends at the far side of the start: reverse it before the forward part
        # walk(s, 1) starts with the start point itself: reversed, it ends there
        pts = [segments[t, f] for t, f in reversed(backward)] or [segments[s, 0]]
        pts += [segments[t, f] for t, f in forward]
        if closed:
            pts = pts[:-1]
        points = _straighten(np.asarray(pts), closed)
        members = [s] + [t for t, _ in forward] + [t for t, _ in backward]
        members = sorted(set(members))
        lines.append(Polyline(points, closed and len(points) >= 3, segments[members],
                              normals[members]))
    return lines


def _straighten(points: np.ndarray, closed: bool) -> np.ndarray:
    """The points without those in the middle of a straight run (a wall cut through many
    triangles is one line)."""
    if len(points) < 3:
        return points
    prev, nxt = np.roll(points, 1, axis=0), np.roll(points, -1, axis=0)
    a, b = points - prev, nxt - points
    cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    scale = np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1)
    keep = (np.abs(cross) > 1e-9 * np.maximum(scale, 1e-30)) | (np.sum(a * b, axis=1) < 0)
    if not closed:
        keep[0] = keep[-1] = True
    return points[keep] if np.count_nonzero(keep) >= (3 if closed else 2) else points


def signed_area(points: np.ndarray) -> float:
    """Shoelace area of a closed polygon (positive counter-clockwise)."""
    x, y = points[:, 0], points[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def _depths(loops: Sequence[np.ndarray]) -> List[int]:
    """How many larger loops contain each loop (quadratic: above 400 loops, all 0)."""
    from matplotlib.path import Path

    paths = [Path(p) for p in loops]
    sizes = [abs(signed_area(p)) for p in loops]
    depths = [0] * len(loops)
    if len(loops) > 400:
        return depths
    for i, loop in enumerate(loops):
        for j, path in enumerate(paths):
            if j != i and sizes[j] > sizes[i] and np.all(path.contains_points(loop,
                                                                            radius=1e-9)):
                depths[i] += 1
    return depths


def fill_orientation(loops: Sequence[np.ndarray]) -> List[np.ndarray]:
    """The loops oriented so that a non-zero fill shows solids with holes: a loop inside an
    odd number of larger loops (the room inside a ring of walls) runs clockwise, the others
    counter-clockwise (overlapping solids then add up instead of cancelling)."""
    out = []
    for loop, depth in zip(loops, _depths(loops)):
        ccw = signed_area(loop) > 0
        out.append(loop if ccw == (depth % 2 == 0) else loop[::-1])
    return out


def _outward_score(line: Polyline, hole: bool) -> float:
    """How far the cut triangles' normals point out of the material (−1 … 1, weighted by
    length): for a loop around material, away from what it encloses; for a hole, into it."""
    from matplotlib.path import Path

    seg = line.segments
    length = np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1)
    norm = np.linalg.norm(line.normals, axis=1)
    ok = norm > 1e-6
    if not np.any(ok) or length[ok].sum() <= 0:
        return 0.0
    mid = seg[ok].mean(axis=1)
    step = 1e-4 * line.normals[ok] / norm[ok, None]
    inside = Path(line.points).contains_points(mid + step)
    sign = np.where(inside, -1.0, 1.0) * (-1.0 if hole else 1.0)
    return float(np.sum(sign * length[ok]) / length[ok].sum())


def solids(lines: Sequence[Polyline]) -> Tuple[List[np.ndarray], List[Polyline]]:
    """Which closed cut outlines enclose material: (the loops to fill, with their holes; the
    rest, drawn as lines). A loop with its holes (the loops directly inside it) is material
    when the cut faces' normals point out of it (closed bodies face outwards); where the
    normals do not tell (single faces wound either way), when it is thin like a wall (area
    over perimeter under THIN_M). A room of single wall faces is therefore not filled."""
    closed = [l for l in lines if l.closed]
    rest = [l for l in lines if not l.closed]
    depths = _depths([l.points for l in closed])
    fill: List[np.ndarray] = []
    for i, line in enumerate(closed):
        if depths[i] % 2:
            continue  # a hole: decided with the loop around it
        holes = [h for j, h in enumerate(closed) if depths[j] == depths[i] + 1 and np.all(
            _inside(line.points, h.points))]
        group = [line] + holes
        weights = [float(np.linalg.norm(np.diff(g.points, axis=0), axis=1).sum())
                   for g in group]
        score = sum(w * _outward_score(g, k > 0) for k, (g, w) in enumerate(
            zip(group, weights))) / max(sum(weights), 1e-12)
        area = abs(signed_area(line.points)) - sum(abs(signed_area(h.points)) for h in holes)
        thin = area / max(sum(weights), 1e-12) < THIN_M
        if score > 0.5 or (score >= -0.5 and thin):
            fill.extend(g.points for g in group)
        else:
            rest.extend(group)
    return fill, rest


def _inside(outer: np.ndarray, inner: np.ndarray) -> np.ndarray:
    from matplotlib.path import Path

    return Path(outer).contains_points(inner, radius=1e-9)


# --- storeys ----------------------------------------------------------------------------------

def floor_below(corners: np.ndarray, z: float, xy: Optional[Tuple[float, float, float, float]],
                depth: float = 3.5) -> Optional[float]:
    """The floor under a work plane at height ``z``: the height, between ``z`` − ``depth`` and
    ``z``, with the most horizontal surface inside the box ``xy`` (x0, x1, y0, y1) and its 1 m
    surroundings (a slab's top rather than its bottom: the highest of the near-largest)."""
    if not len(corners):
        return None
    normals = unit_normals(corners)
    centre = corners.mean(axis=1)
    ok = (np.abs(normals[:, 2]) > 0.999) & (centre[:, 2] <= z + 1e-3) & (
        centre[:, 2] >= z - depth)
    if xy is not None:
        x0, x1, y0, y1 = xy
        ok &= (centre[:, 0] >= x0 - 1) & (centre[:, 0] <= x1 + 1) & (
            centre[:, 1] >= y0 - 1) & (centre[:, 1] <= y1 + 1)
    if not np.any(ok):
        return None
    heights = np.round(centre[ok, 2], 3)
    found, index = np.unique(heights, return_inverse=True)
    total = np.bincount(index, weights=areas(corners[ok]))
    return float(found[total >= 0.9 * total.max()].max())


def find_levels(corners: np.ndarray, anchors: Iterable[Tuple[float, Optional[Tuple]]],
                lowest_item_z: Optional[float]) -> List[Level]:
    """The storeys of a model: one per distinct floor under its horizontal calculation grids
    (``anchors``: each grid's height and x-y box), else one under the lowest luminaire or
    target (``lowest_item_z``) or at the lowest geometry."""
    floors = []
    for z, box in anchors:
        floor = floor_below(corners, z, box)
        floors.append(z - 0.8 if floor is None else floor)
    if not floors:
        top = lowest_item_z if lowest_item_z is not None else (
            float(corners[:, :, 2].max()) if len(corners) else 0.0)
        floor = floor_below(corners, top, None, depth=math.inf)
        floors = [floor if floor is not None else (
            float(corners[:, :, 2].min()) if len(corners) else 0.0)]
    merged: List[float] = []
    for f in sorted(floors):
        if not merged or f - merged[-1] >= STOREY_MIN_M:
            merged.append(f)
    levels = []
    for i, f in enumerate(merged):
        top = merged[i + 1] if i + 1 < len(merged) else math.inf
        levels.append(Level(f, clear_height(corners, f + CUT_HEIGHT_M), top,
                            f if i else -math.inf))
    return levels


# --- the plan of a level ------------------------------------------------------------------------

def drawn_edges(corners: np.ndarray, crease_deg: float = CREASE_DEG) -> np.ndarray:
    """Edges (e, 2, 3) a drawing shows: a face's free edges, edges where three or more faces
    meet and creases; not the seam between two coplanar triangles. Edges are matched by
    their end points' positions (meshes often repeat vertices per face)."""
    if not len(corners):
        return np.zeros((0, 2, 3))
    starts = corners.reshape(-1, 3)
    ends = np.roll(corners, -1, axis=1).reshape(-1, 3)
    a = np.round(starts / WELD_M).astype(np.int64)
    b = np.round(ends / WELD_M).astype(np.int64)
    diff = a - b  # order each edge's ends lexicographically, so both faces give one key
    lead = diff[np.arange(len(diff)), np.argmax(diff != 0, axis=1)]
    a_first = (lead <= 0)[:, None]
    first, second = np.where(a_first, a, b), np.where(a_first, b, a)
    keys = np.concatenate([first, second], axis=1)
    _, first_at, inverse, counts = np.unique(keys, axis=0, return_index=True,
                                             return_inverse=True, return_counts=True)
    inverse = inverse.ravel()
    draw = counts != 2  # per distinct edge: free edges and junctions of 3+ faces
    # Edges of exactly two faces: drawn where the faces' normals differ (either winding).
    grouped = np.argsort(inverse, kind="stable")
    group_start = np.concatenate([[0], np.cumsum(counts)[:-1]])
    pairs = np.flatnonzero(counts == 2)
    one, two = grouped[group_start[pairs]], grouped[group_start[pairs] + 1]
    normals = np.repeat(unit_normals(corners), 3, axis=0)
    cos = np.abs(np.sum(normals[one] * normals[two], axis=1))
    draw[pairs[cos < math.cos(math.radians(crease_deg))]] = True
    keep = np.sort(first_at[draw])
    return np.stack([starts[keep], ends[keep]], axis=1)


def _distinct_2d(edges: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Edges (e, 2, 3) projected: (edges (k, 2, 2), their heights), without the points
    (vertical edges) and without repeats (a box's top and bottom edges fall on each other:
    the highest is kept, the one seen from above)."""
    flat = edges[:, :, :2]
    keep = np.linalg.norm(flat[:, 1] - flat[:, 0], axis=1) > 1e-4
    flat, heights = flat[keep], edges[keep][:, :, 2].max(axis=1)
    if not len(flat):
        return flat, heights
    order = np.argsort(-heights, kind="stable")  # highest first: unique keeps the first
    flat, heights = flat[order], heights[order]
    keys = np.round(flat / WELD_M).astype(np.int64)
    swap = (keys[:, 0, 0] > keys[:, 1, 0]) | (
        (keys[:, 0, 0] == keys[:, 1, 0]) & (keys[:, 0, 1] > keys[:, 1, 1]))
    keys[swap] = keys[swap][:, ::-1]
    _, first = np.unique(keys.reshape(-1, 4), axis=0, return_index=True)
    first = np.sort(first)
    return flat[first], heights[first]


def _layer(mesh: Mesh, level: Level) -> Optional[Layer]:
    """The mesh's triangles below the section and above the floor, projected, lowest first,
    with its drawn edges."""
    corners = mesh.corners
    if not len(corners):
        return None
    low, high = corners[:, :, 2].min(axis=1), corners[:, :, 2].max(axis=1)
    below = (high <= level.cut_z) & (low >= level.floor_z - 0.05)
    if not np.any(below):
        return None
    corners, high = corners[below], high[below]
    if len(corners) > TOP_VIEW_MAX:  # a huge mesh: its larger faces (the rest is too small
        keep = np.sort(np.argsort(-areas(corners), kind="stable")[:TOP_VIEW_MAX])  # to see)
        corners, high = corners[keep], high[keep]
    edges, edge_heights = _distinct_2d(drawn_edges(corners))
    seen = np.abs(unit_normals(corners)[:, 2]) > 0.05  # vertical faces have no area in plan
    tops = high[seen]
    order = np.argsort(tops, kind="stable")
    return Layer(mesh, corners[seen][order][:, :, :2], tops[order], edges, float(high.max()),
                 edge_heights)


def section(meshes: Sequence[Mesh], level: Level) -> Section:
    """The plan geometry of one storey: what the horizontal plane at ``level.cut_z`` cuts, as
    walls (meshes reaching up to nearly the highest cut one: walls, full-height cupboards),
    furniture (lower cut objects: a cabinet, a window frame) and glass, each chained over all
    meshes (a wall whose inner face is a separate target mesh still closes); and each mesh's
    triangles below the cut and above the floor, lowest first."""
    out = Section(level)
    cuts = []
    for mesh in meshes:
        segs, normals = cut_segments(mesh.corners, level.cut_z)
        if len(segs):
            cuts.append((mesh, segs, normals, float(mesh.corners[:, :, 2].max())))
        layer = _layer(mesh, level)
        if layer is not None:
            out.layers.append(layer)
    out.layers.sort(key=lambda l: l.top_z)
    highest = max([min(top, level.top_z) for _, _, _, top in cuts], default=level.cut_z)
    wall_top = level.floor_z + WALL_SHARE * (highest - level.floor_z)
    groups: Dict[str, List[Polyline]] = {"walls": [], "furniture": [], "glass": []}
    for mesh, segs, normals, top in cuts:
        kind = "glass" if mesh.kind == "glass" else "walls" if top >= wall_top else "furniture"
        if kind == "walls":
            out.wall_meshes.append(mesh)
        groups[kind].extend(chain(segs, normals))
    out.walls, out.furniture, out.glass = (_join(groups[k]) for k in
                                           ("walls", "furniture", "glass"))
    return out


def _join(lines: List[Polyline]) -> List[Polyline]:
    """Each mesh's closed outlines as they are; the open chains of all meshes chained again
    together (a wall whose inner face is a separate target mesh closes then), so that bodies
    touching each other (two wall boxes at a corner) keep their own closed outlines."""
    closed = [l for l in lines if l.closed]
    loose = [l for l in lines if not l.closed]
    if not loose:
        return closed
    return closed + chain(np.concatenate([l.segments for l in loose]),
                          np.concatenate([l.normals for l in loose]))

