# SPDX-License-Identifier: LGPL-2.1-or-later
"""The room's own frame for the picture of the model (axonometric.py): a room not aligned
with the model's axes is seen from above its own corner, and its own near walls are left
out, by turning the view (and the tests for near walls) with the room."""
from __future__ import annotations

import math
from typing import Sequence, Tuple

import numpy as np

from lightsolver_report.meshes import Mesh
from lightsolver_report.section import Level


def rotate_z(points: np.ndarray, angle_deg: float) -> np.ndarray:
    """Points (..., 3) turned by ``angle_deg`` about the vertical (counter-clockwise)."""
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    out = points.copy()
    out[..., 0] = c * points[..., 0] - s * points[..., 1]
    out[..., 1] = s * points[..., 0] + c * points[..., 1]
    return out


def room_angle(meshes: Sequence[Mesh], level: Level) -> float:
    """The room's orientation (degrees, in (−45, 45]): the direction of the storey's upright
    faces (walls), weighted by area, modulo 90° (a rectangular room's four walls agree); 0 for
    a room along the axes or without upright faces."""
    sx = sy = 0.0
    for mesh in meshes:
        corners = mesh.corners
        if not len(corners):
            continue
        low, high = corners[:, :, 2].min(axis=1), corners[:, :, 2].max(axis=1)
        mine = (high > level.floor_z + 0.05) & (low < level.top_z - 0.05)
        cross = np.cross(corners[mine, 1] - corners[mine, 0], corners[mine, 2] - corners[mine, 0])
        horizontal = np.hypot(cross[:, 0], cross[:, 1])  # twice the area, as seen sideways
        upright = horizontal > 10 * np.abs(cross[:, 2])
        phi = 4.0 * np.arctan2(cross[upright, 1], cross[upright, 0])
        sx += float(np.sum(horizontal[upright] * np.cos(phi)))
        sy += float(np.sum(horizontal[upright] * np.sin(phi)))
    if math.hypot(sx, sy) < 1e-12:
        return 0.0
    angle = math.degrees(math.atan2(sy, sx)) / 4.0
    angle = round(angle, 6) + 0.0  # 0.0 for an axis-aligned room (not -0.0 or 1e-15)
    return 45.0 if angle == -45.0 else angle


def room_box(meshes: Sequence[Mesh], level: Level, angle_deg: float, margin: float = 0.4
             ) -> Tuple[float, float, float, float]:
    """(x0, x1, y0, y1) of the storey's geometry in the room's frame (turned by −angle), with
    the plan's margin."""
    parts = []
    for mesh in meshes:
        corners = mesh.corners
        if len(corners):
            low, high = corners[:, :, 2].min(axis=1), corners[:, :, 2].max(axis=1)
            parts.append(corners[(high > level.floor_z - 0.05) & (low < level.top_z - 0.05)])
    pts = rotate_z(np.concatenate(parts).reshape(-1, 3), -angle_deg) if parts else np.zeros(
        (1, 3))
    if not len(pts):
        pts = np.zeros((1, 3))
    return (float(pts[:, 0].min()) - margin, float(pts[:, 0].max()) + margin,
            float(pts[:, 1].min()) - margin, float(pts[:, 1].max()) + margin)
