# SPDX-License-Identifier: LGPL-2.1-or-later
"""The floor area of a room as the model draws it: LENI's area (EN 15193-1's useful floor
area) where the designer states none.

The storey's floor (upward faces at its floor height) is rasterised on the plan, the walls'
upright faces (of the meshes the section cuts as walls) drawn across it as lines, and the floor
is filled from each calculation grid's centre without crossing a line. A wall above a door or
a window still projects onto the plan, so openings do not let the fill out; a floor that the
fill can leave without meeting a wall (an open slab, a wall missing) has no room, and the
caller falls back to the grid's own area. Cells are at most 20 mm (larger floors: as many as
fit 250 000 cells); the cells the wall lines run through count half, so the area is exact for
walls along the axes on multiples of 20 mm and otherwise within about a fifth of a cell times
the walls' length (the office turned 30°: 19.94 m² for 20 m²)."""
from __future__ import annotations

import math
from typing import Optional, Sequence, Tuple

import numpy as np

from lightsolver_report.meshes import Mesh
from lightsolver_report.section import Level, unit_normals

#: Largest cell (m) and most cells of the raster.
CELL_M = 0.02
MAX_CELLS = 250_000
#: A face lies on the floor within this height (m).
ON_FLOOR_M = 2e-3


class _Raster:
    """Cells over a box (with a border): cell (i, j) is centred at (x0 + (j + ½) c,
    y0 + (i + ½) c)."""

    def __init__(self, box: Tuple[float, float, float, float]) -> None:
        x0, x1, y0, y1 = box
        self.cell = max(CELL_M, math.sqrt((x1 - x0) * (y1 - y0) / MAX_CELLS))
        # Cell centres on multiples of the cell, so that walls on round coordinates run
        # through the middle of their cells (counted half: exact); a free border all round.
        self.x0 = (math.floor(x0 / self.cell) - 1.5) * self.cell
        self.y0 = (math.floor(y0 / self.cell) - 1.5) * self.cell
        self.nx = int(math.ceil((x1 - self.x0) / self.cell)) + 2
        self.ny = int(math.ceil((y1 - self.y0) / self.cell)) + 2

    def index(self, x: np.ndarray, y: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        i = np.clip(np.floor((y - self.y0) / self.cell).astype(np.int64), 0, self.ny - 1)
        j = np.clip(np.floor((x - self.x0) / self.cell).astype(np.int64), 0, self.nx - 1)
        return i, j

    def triangles(self, tris: np.ndarray) -> np.ndarray:
        """Cells whose centre lies in one of the triangles (k, 3, 2) (the picture's rasteriser,
        vectorised: a floor of many triangles costs no Python loop)."""
        from lightsolver_report.zbuffer import coverage

        pixels = np.stack([(tris[..., 0] - self.x0) / self.cell,
                           (tris[..., 1] - self.y0) / self.cell], axis=-1)
        return coverage(pixels, self.nx, self.ny).reshape(self.ny, self.nx)

    def lines(self, segments: np.ndarray) -> np.ndarray:
        """Cells a segment (k, 2, 2) passes through (sampled at a third of a cell; repeated
        segments once, in batches of at most a million samples)."""
        mask = np.zeros((self.ny, self.nx), dtype=bool)
        if not len(segments):
            return mask
        keys = np.round(segments / (self.cell / 8.0)).astype(np.int64).reshape(-1, 4)
        segments = segments[np.sort(np.unique(keys, axis=0, return_index=True)[1])]
        length = np.linalg.norm(segments[:, 1] - segments[:, 0], axis=1)
        steps = np.ceil(length / (self.cell / 3.0)).astype(np.int64) + 1
        ends = np.cumsum(steps)
        start = 0
        while start < len(segments):
            stop = max(start + 1, int(np.searchsorted(ends, ends[start] - steps[start]
                                                      + 1_000_000, side="right")))
            part, n = segments[start:stop], steps[start:stop]
            which = np.repeat(np.arange(len(part)), n)
            t = (np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)) / np.repeat(
                np.maximum(n - 1, 1), n)
            pts = part[which, 0] + t[:, None] * (part[which, 1] - part[which, 0])
            mask[self.index(pts[:, 0], pts[:, 1])] = True
            start = stop
        return mask


def _grow(mask: np.ndarray) -> np.ndarray:
    """The cells 4-adjacent to ``mask`` or in it."""
    out = mask.copy()
    out[1:] |= mask[:-1]
    out[:-1] |= mask[1:]
    out[:, 1:] |= mask[:, :-1]
    out[:, :-1] |= mask[:, 1:]
    return out


def _fill(free: np.ndarray, seeds: Sequence[Tuple[int, int]]) -> np.ndarray:
    """The cells of ``free`` 4-connected to the seeds."""
    fill = np.zeros_like(free)
    for i, j in seeds:
        fill[i, j] = True
    while True:
        grown = fill
        for _ in range(16):  # check for the end now and then: comparing costs as much
            grown = _grow(grown) & free
        if np.array_equal(grown, fill):
            return fill
        fill = grown


def _wall_lines(walls: Sequence[Mesh], level: Level) -> np.ndarray:
    """The plan lines of the walls' upright faces within the storey."""
    parts = []
    for mesh in walls:
        corners = mesh.corners
        if not len(corners):
            continue
        upright = np.abs(unit_normals(corners)[:, 2]) < 0.999
        low, high = corners[:, :, 2].min(axis=1), corners[:, :, 2].max(axis=1)
        mine = upright & (high > level.floor_z + 0.05) & (low < level.top_z - 0.05)
        tris = corners[mine][:, :, :2]
        parts.append(np.stack([tris, np.roll(tris, -1, axis=1)], axis=2).reshape(-1, 2, 2))
    return np.concatenate(parts) if parts else np.zeros((0, 2, 2))


def room_floor_area(meshes: Sequence[Mesh], walls: Sequence[Mesh], level: Level,
                    points: Sequence[Tuple[float, float]]) -> Optional[float]:
    """The floor area (m²) of the rooms holding ``points`` (each counted once), or None where
    a point is not over the floor or its floor is not enclosed by walls."""
    if not points or not walls:
        return None
    corners = np.concatenate([m.corners for m in meshes if len(m.triangles)] or
                             [np.zeros((0, 3, 3))])
    if not len(corners):
        return None
    up = (unit_normals(corners)[:, 2] > 0.999) & np.all(
        np.abs(corners[:, :, 2] - level.floor_z) <= ON_FLOOR_M, axis=1)
    floor = corners[up][:, :, :2]
    if not len(floor):
        return None
    flat = floor.reshape(-1, 2)
    raster = _Raster((float(flat[:, 0].min()), float(flat[:, 0].max()),
                      float(flat[:, 1].min()), float(flat[:, 1].max())))
    barrier = raster.lines(_wall_lines(walls, level))
    floor_cells = raster.triangles(floor)
    free = floor_cells & ~barrier
    px = np.array([p[0] for p in points], dtype=float)
    py = np.array([p[1] for p in points], dtype=float)
    seeds = list(zip(*raster.index(px, py)))
    if not all(free[i, j] for i, j in seeds):
        return None
    fill = _fill(free, seeds)
    if np.any(_grow(fill) & ~floor_cells & ~barrier):
        return None  # the fill reached the floor's edge where no wall stands: no room
    rim = _grow(fill) & barrier & ~fill
    return float((fill.sum() + 0.5 * rim.sum()) * raster.cell ** 2)
