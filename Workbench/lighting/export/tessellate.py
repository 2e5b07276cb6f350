# SPDX-License-Identifier: LGPL-2.1-or-later
"""OpenCASCADE tessellation per face, and a mesh builder that converts mm -> m."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

from lighting.units import MM_TO_M

Triangle = Tuple[int, int, int]


@dataclass
class FaceTriangles:
    """Triangles of one face: points in mm (global), counter-clockwise seen from the front."""

    points_mm: List[Any]
    triangles: List[Triangle]


def tessellate_faces(shape: Any, linear_mm: float, angular_deg: float
                     ) -> Tuple[List[Optional[FaceTriangles]], List[str]]:
    """Triangulate every face of ``shape``; returns one entry per face (None where it failed)
    and the failure messages.

    The whole shape is meshed first (MeshPart with the linear and angular deflection), so
    neighbouring faces share their edge points and closed solids stay closed; each face's
    triangles are then read back in the face's orientation (front = outward normal)."""
    import MeshPart

    errors: List[str] = []
    try:
        MeshPart.meshFromShape(Shape=shape, LinearDeflection=linear_mm,
                               AngularDeflection=math.radians(angular_deg), Relative=False)
    except Exception as exc:  # noqa: BLE001 - fall back to face by face below
        errors.append(f"meshing the whole shape failed ({exc}); trying face by face")
    result: List[Optional[FaceTriangles]] = []
    for index, face in enumerate(shape.Faces):
        try:
            points, triangles = face.tessellate(linear_mm)
        except Exception as exc:  # noqa: BLE001
            errors.append(f"Face{index + 1} could not be tessellated ({exc})")
            result.append(None)
            continue
        if not triangles:
            try:
                area = face.Area
            except Exception:  # noqa: BLE001
                area = 1.0
            if area > 1e-6:
                errors.append(f"Face{index + 1} gave no triangles")
            result.append(None)
            continue
        result.append(FaceTriangles(list(points), [tuple(t) for t in triangles]))
    return result, errors


def mesh_triangles(mesh: Any) -> FaceTriangles:
    """Points (mm) and facets of a Mesh.Mesh, placement applied."""
    points, facets = mesh.Topology
    return FaceTriangles(list(points), [tuple(f) for f in facets])


@dataclass
class MeshBuilder:
    """Accumulates triangles in metres, merging identical vertices, dropping degenerate ones."""

    name: str
    material: str
    vertices: List[List[float]] = field(default_factory=list)
    triangles: List[List[int]] = field(default_factory=list)
    dropped: int = 0
    _index: Dict[Tuple[float, float, float], int] = field(default_factory=dict, repr=False)

    def _vertex(self, point_mm: Any) -> int:
        key = (round(point_mm.x * MM_TO_M, 9), round(point_mm.y * MM_TO_M, 9),
               round(point_mm.z * MM_TO_M, 9))
        index = self._index.get(key)
        if index is None:
            index = len(self.vertices)
            self._index[key] = index
            self.vertices.append(list(key))
        return index

    def add(self, part: FaceTriangles, flip: bool = False) -> int:
        """Append a face's triangles (flipped if asked); returns the number added."""
        local = [self._vertex(p) for p in part.points_mm]
        added = 0
        for a, b, c in part.triangles:
            ia, ib, ic = local[a], local[b], local[c]
            if flip:
                ib, ic = ic, ib
            if ia == ib or ib == ic or ia == ic or self._area2(ia, ib, ic) <= 1e-18:
                self.dropped += 1
                continue
            self.triangles.append([ia, ib, ic])
            added += 1
        return added

    def _area2(self, ia: int, ib: int, ic: int) -> float:
        a, b, c = self.vertices[ia], self.vertices[ib], self.vertices[ic]
        u = (b[0] - a[0], b[1] - a[1], b[2] - a[2])
        v = (c[0] - a[0], c[1] - a[1], c[2] - a[2])
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        return n[0] * n[0] + n[1] * n[1] + n[2] * n[2]

    def scene_entry(self) -> Dict[str, Any]:
        """Inline ``meshes[]`` entry of the scene."""
        return {"name": self.name, "material": self.material, "vertices": self.vertices,
                "triangles": self.triangles}


def triangle_normal(part: FaceTriangles, index: int = 0) -> Tuple[Any, Any]:
    """(centroid, unnormalised normal) of one triangle of a face, in mm."""
    a, b, c = (part.points_mm[i] for i in part.triangles[index])
    return (a + b + c) * (1.0 / 3.0), (b - a).cross(c - a)


def largest_triangle(part: FaceTriangles) -> int:
    """Index of the triangle with the largest area (a stable probe for orientation tests)."""
    best, best_area = 0, -1.0
    for i, _ in enumerate(part.triangles):
        area = triangle_normal(part, i)[1].Length
        if area > best_area:
            best, best_area = i, area
    return best
