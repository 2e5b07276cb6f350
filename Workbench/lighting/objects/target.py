# SPDX-License-Identifier: LGPL-2.1-or-later
"""Target: where illuminance is reported — selected faces, or a calculation grid.

Face targets report the mean illuminance on the front (outward) side of exactly the selected
faces. Grid targets are rectangles of cells with the EN 12464-1 spacing unless one is set and
a border band left out; by their ``Surface`` kind:

* *Work plane*: horizontal at work-plane height over a floor, slab, space or floor face;
* *Wall*, *Ceiling*, *Floor*: on one planar face of any orientation (a wall's inner face, a
  ceiling's underside), ``Offset`` in front of it, facing the room (the face's outward
  normal; for an Arch space's faces, the inward one). A Floor grid without a face lies
  ``Offset`` above the floor like a work plane.

``Activity`` presets the requirements (EN 12464-1 rows in lighting.standards) for the kind.
A target is an input only: its results live in the analysis' results object
(objects/results.py)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

import FreeCAD

from lighting import standards
from lighting.compat import ifc_type
from lighting.geometry import (face_index, face_normal, global_shape, is_planar,
                               offset_for_display, referenced_faces)
from lighting.objects import daylight_target
from lighting.objects.base import BaseProxy, Prop, READ_ONLY
from lighting.objects.daylight_target import DAYLIGHT_PROPERTIES
from lighting.units import MM_TO_M, M_TO_MM, vec_m

TYPE = "Lighting::Target"
TARGET_TYPES = ("Faces", "Grid")
_RO = READ_ONLY

@dataclass
class GridRect:
    """A calculation grid in millimetres: ``corner + s*edge1 + t*edge2``, facing edge1 x edge2."""

    corner: FreeCAD.Vector
    edge1: FreeCAD.Vector
    edge2: FreeCAD.Vector
    nu: int
    nv: int
    spacing_mm: float

    def cell_corners(self, iu: int, iv: int) -> List[FreeCAD.Vector]:
        """The four corners of cell (iu, iv), counter-clockwise seen from the front."""
        du, dv = self.edge1 * (1.0 / self.nu), self.edge2 * (1.0 / self.nv)
        p0 = self.corner + du * iu + dv * iv
        return [p0, p0 + du, p0 + du + dv, p0 + dv]

    def scene_entry(self, name: str) -> Dict[str, Any]:
        """The grid as a ``targets[]`` entry of docs/scene-format.md (metres)."""
        return {"name": name, "type": "grid", "corner": vec_m(self.corner),
                "edge1": vec_m(self.edge1), "edge2": vec_m(self.edge2),
                "cells": [self.nu, self.nv]}

    @property
    def normal(self) -> FreeCAD.Vector:
        """Unit normal of the front (the side whose light is counted): edge1 x edge2."""
        return self.edge1.cross(self.edge2).normalize()

    @property
    def size_m(self) -> Tuple[float, float]:
        """Lengths of edge1 and edge2 in metres."""
        return self.edge1.Length * MM_TO_M, self.edge2.Length * MM_TO_M

    def axes(self) -> Tuple[FreeCAD.Vector, FreeCAD.Vector]:
        """Unit vectors along edge1 and edge2 (new vectors: Vector.normalize() works in place)."""
        return (self.edge1 * (1.0 / self.edge1.Length), self.edge2 * (1.0 / self.edge2.Length))

    def point(self, u_m: float, v_m: float, lift_mm: float = 0.0) -> FreeCAD.Vector:
        """The global point (mm) at (u, v) metres from the corner, ``lift_mm`` in front."""
        u, v = self.axes()
        return self.corner + u * (u_m * M_TO_MM) + v * (v_m * M_TO_MM) + self.normal * lift_mm


class Target(BaseProxy):
    """Illuminance target (faces or grid)."""

    TYPE = TYPE
    PROPERTIES = {
        "TargetType": Prop("App::PropertyEnumeration", "Target",
                           "Faces: mean illuminance on the selected faces' front side; Grid: "
                           "calculation grid over a floor/space at work-plane height",
                           "Faces", items=TARGET_TYPES),
        "References": Prop("App::PropertyLinkSubList", "Target",
                           "Faces target: the faces (front = outward face normal)"),
        "Base": Prop("App::PropertyLinkSub", "Grid",
                     "Grid target: floor, slab, Arch space or floor face (work plane); a planar "
                     "face of any orientation (wall, ceiling, floor grids)"),
        "WorkplaneHeight": Prop("App::PropertyLength", "Grid",
                                "Height of the grid above the floor (EN 12464-1: 0.80 m)",
                                standards.WORKPLANE_HEIGHT_M * M_TO_MM),
        "WallBand": Prop("App::PropertyLength", "Grid",
                         "Border band left out of the grid (EN 12464-1: 0.5 m along the walls "
                         "for task areas; walls and ceilings: 0)",
                         standards.WALL_BAND_M * M_TO_MM),
        "Spacing": Prop("App::PropertyLength", "Grid",
                        "Grid spacing; 0 = EN 12464-1 rule p = 0.2*5^log10(d)", 0.0),
        "SpacingUsed": Prop("App::PropertyLength", "Grid", "Grid spacing in use", 0.0, _RO),
        "CellsU": Prop("App::PropertyInteger", "Grid", "Cells along X (edge1)", 0, _RO),
        "CellsV": Prop("App::PropertyInteger", "Grid", "Cells along Y (edge2)", 0, _RO),
        "RequiredLux": Prop("App::PropertyFloat", "Requirements",
                            "Required maintained illuminance Em in lx (0 = none); EN 12464-1 "
                            "office desk work: 500", 0.0),
        "RequiredUniformity": Prop("App::PropertyFloat", "Requirements",
                                   "Required uniformity U0 (0 = none); office task area: 0.60", 0.0),
        "Surface": Prop("App::PropertyEnumeration", "Grid",
                        "What the grid measures: Work plane (horizontal at WorkplaneHeight), "
                        "Wall, Ceiling or Floor (on the Base face, Offset in front of it)",
                        "Work plane", items=standards.SURFACE_KINDS),
        "Offset": Prop("App::PropertyLength", "Grid",
                       "Wall, ceiling and floor grids: distance in front of the face",
                       standards.SURFACE_OFFSET_M * M_TO_MM),
        "Activity": Prop("App::PropertyEnumeration", "Requirements",
                         "EN 12464-1 preset of RequiredLux/RequiredUniformity for the Surface "
                         "kind (walls, ceilings: U0 0.10); Custom = as typed",
                         standards.CUSTOM, items=standards.ACTIVITIES),
        # Daylight-factor grids (docs/scene-format.md, "Targets"; objects/daylight_target.py).
        **DAYLIGHT_PROPERTIES,
    }

    def onChanged(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        """Keep the requirements and the Activity preset in step (either way round)."""
        if not {"Activity", "Surface", "RequiredLux"} <= set(obj.PropertiesList):
            return  # still being built
        if getattr(obj.Document, "Restoring", False):
            return
        if prop in ("Surface", "Activity"):
            apply_preset(obj)
        elif prop in ("RequiredLux", "RequiredUniformity"):
            wanted = preset_of(obj)
            if wanted is None:
                return
            preset = wanted.lux if prop == "RequiredLux" else wanted.uniformity
            if float(getattr(obj, prop)) != preset:
                obj.Activity = standards.CUSTOM  # typed by hand: no preset any more

    def execute(self, obj: Any) -> None:
        """Rebuild the display shape: grid cells, or the selected faces lifted by 1 mm."""
        import Part

        if obj.TargetType == "Grid":
            try:
                rect = grid_rectangle(obj)
            except ValueError as exc:
                FreeCAD.Console.PrintWarning(f"{exc}\n")
                obj.Shape = Part.Shape()
                return
            if obj.CellsU != rect.nu or obj.CellsV != rect.nv:
                obj.CellsU, obj.CellsV = rect.nu, rect.nv
            if abs(float(obj.SpacingUsed) - rect.spacing_mm) > 1e-9:
                obj.SpacingUsed = rect.spacing_mm
            obj.Shape = grid_display_shape(rect)
        else:
            try:
                faces = [offset_for_display(face, 1.0) for _, _, face in
                         referenced_faces(obj.References)]
            except ValueError as exc:
                FreeCAD.Console.PrintWarning(f"Target '{obj.Label}': {exc}\n")
                faces = []
            obj.Shape = Part.makeCompound(faces) if faces else Part.Shape()
        # The shape is already in global coordinates.
        obj.Placement = FreeCAD.Placement()


def preset_of(obj: Any) -> Optional[standards.Requirement]:
    """The requirement the target's Activity presets for its Surface kind (None: Custom)."""
    return standards.requirement(obj.Activity, obj.Surface)


def apply_preset(obj: Any) -> None:
    """Write the Activity preset into RequiredLux/RequiredUniformity (Custom: unchanged)."""
    wanted = preset_of(obj)
    if wanted is None:
        return
    if float(obj.RequiredLux) != wanted.lux:
        obj.RequiredLux = wanted.lux
    if float(obj.RequiredUniformity) != wanted.uniformity:
        obj.RequiredUniformity = wanted.uniformity


def requirements_entry(obj: Any) -> Dict[str, Any]:
    """The target's requirements as scene-entry keys (docs/scene-format.md): ``task`` (the
    table row of a task-area preset, so results and reports name it) and ``requirements``
    with the values the document holds (they replace the row's). The solver judges them from
    the intervals; a face target takes only Em. Empty without requirements."""
    if daylight_target.is_daylight_factor(obj):
        return daylight_target.requirements_entry(obj)
    entry: Dict[str, Any] = {}
    is_grid = obj.TargetType == "Grid"
    task = standards.task_of(obj.Activity) if "Activity" in obj.PropertiesList else None
    if task is not None and is_grid and obj.Surface in ("Work plane", "Floor"):
        entry["task"] = task.id
    wanted: Dict[str, float] = {}
    if float(obj.RequiredLux) > 0.0:
        wanted["em_lux"] = float(obj.RequiredLux)
    if is_grid and float(obj.RequiredUniformity) > 0.0:
        wanted["u0"] = float(obj.RequiredUniformity)
    if wanted:
        entry["requirements"] = wanted
    return entry


def grid_display_shape(rect: GridRect) -> Any:
    """Compound with one face per cell, in cell order (index = iv*nu + iu), for colouring."""
    import Part

    if rect.nu * rect.nv > 40000:  # too many faces to draw one by one: one plain face
        corners = [rect.corner, rect.corner + rect.edge1, rect.corner + rect.edge1 + rect.edge2,
                   rect.corner + rect.edge2]
        return Part.makeCompound([Part.Face(Part.makePolygon(corners + [corners[0]]))])
    faces = []
    for iv in range(rect.nv):
        for iu in range(rect.nu):
            corners = rect.cell_corners(iu, iv)
            faces.append(Part.Face(Part.makePolygon(corners + [corners[0]])))
    return Part.makeCompound(faces)


def _floor_outline(base: Any, subs: Tuple[str, ...]) -> Tuple[Any, float]:
    """Bounding box (global XY) of the floor area and the floor level z, in mm."""
    shape = global_shape(base)
    faces = [shape.Faces[i] for i in (face_index(s) for s in subs) if i is not None
             and i < len(shape.Faces)]
    if faces:
        bb = faces[0].BoundBox
        for face in faces[1:]:
            bb.add(face.BoundBox)
        return bb, bb.ZMax
    bb = shape.BoundBox
    if ifc_type(base) == "space":
        return bb, bb.ZMin
    # Floor or slab: the up-facing faces at the top.
    tops = []
    for face in shape.Faces:
        try:
            u0, u1, v0, v1 = face.ParameterRange
            n = face.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1))
        except Exception:  # noqa: BLE001 - degenerate face
            continue
        if n.z > 0.99 and abs(face.BoundBox.ZMax - bb.ZMax) < 1.0:
            tops.append(face)
    if tops:
        top = tops[0].BoundBox
        for face in tops[1:]:
            top.add(face.BoundBox)
        return top, bb.ZMax
    return bb, bb.ZMax


def _base_of(obj: Any) -> Tuple[Any, Tuple[str, ...]]:
    """The grid's Base object and sub-element names; ValueError when there is none."""
    link = obj.Base
    if not link or link[0] is None:
        raise ValueError(f"Grid target '{obj.Label}' has no Base: select a floor, slab, Arch "
                         "space or floor face, or a planar wall or ceiling face")
    base, subs = link[0], tuple(link[1] or ())
    if not hasattr(base, "Shape") or base.Shape.isNull():
        raise ValueError(f"Grid target '{obj.Label}': Base '{base.Label}' has no shape")
    return base, subs


def _cells(obj: Any, length_u_mm: float, length_v_mm: float) -> Tuple[int, int, float]:
    """Cells along u and v and the spacing (mm) for a rectangle, EN 12464-1 unless set."""
    nu, nv, p_m = standards.grid_cells(length_u_mm * MM_TO_M, length_v_mm * MM_TO_M,
                                       float(obj.Spacing) * MM_TO_M)
    return nu, nv, p_m * M_TO_MM


def _no_area(obj: Any, base: Any, length_u_mm: float, length_v_mm: float,
             band_name: str = "wall band") -> ValueError:
    band = float(obj.WallBand)
    return ValueError(f"Grid target '{obj.Label}': the {band_name} of {band / 1000:g} m leaves "
                      f"no area on '{base.Label}' ({length_u_mm / 1000:g} x "
                      f"{length_v_mm / 1000:g} m)")


def _horizontal_grid(obj: Any, base: Any, subs: Tuple[str, ...], height_mm: float) -> GridRect:
    """A horizontal grid ``height_mm`` above the floor level, over the floor's XY extent."""
    bb, floor_z = _floor_outline(base, subs)
    band = float(obj.WallBand)
    x0, x1 = bb.XMin + band, bb.XMax - band
    y0, y1 = bb.YMin + band, bb.YMax - band
    if x1 - x0 <= 1.0 or y1 - y0 <= 1.0:
        raise _no_area(obj, base, bb.XLength, bb.YLength)
    nu, nv, p_mm = _cells(obj, x1 - x0, y1 - y0)
    z = floor_z + height_mm
    return GridRect(FreeCAD.Vector(x0, y0, z), FreeCAD.Vector(x1 - x0, 0, 0),
                    FreeCAD.Vector(0, y1 - y0, 0), nu, nv, p_mm)


def room_side_normal(base: Any, face: Any) -> FreeCAD.Vector:
    """Unit normal of a face toward the room: the outward normal of a wall's or slab's face,
    the inward one of an Arch space's face (a space is the room itself)."""
    normal = face_normal(face)
    return normal * -1.0 if ifc_type(base) == "space" else normal


def face_axes(normal: FreeCAD.Vector) -> Tuple[FreeCAD.Vector, FreeCAD.Vector]:
    """Unit in-plane axes (u, v) with u x v = normal, as seen from the front: on walls u runs
    horizontally and v up; on ceilings and floors u runs along global +X."""
    n = FreeCAD.Vector(normal).normalize()
    if abs(n.z) < 0.7071:
        up = FreeCAD.Vector(0, 0, 1)
        v = (up - n * up.dot(n)).normalize()
        return v.cross(n).normalize(), v
    x = FreeCAD.Vector(1, 0, 0)
    u = (x - n * x.dot(n)).normalize()
    return u, n.cross(u).normalize()


def _face_points(face: Any) -> List[FreeCAD.Vector]:
    """Points on the face's boundary: vertices and points along curved edges."""
    points = [v.Point for v in face.Vertexes]
    for edge in face.Edges:
        try:
            points.extend(edge.discretize(16))
        except Exception:  # noqa: BLE001 - degenerate edge: its vertices are enough
            pass
    return points


def _surface_grid(obj: Any, base: Any, subs: Tuple[str, ...]) -> GridRect:
    """A grid on one planar face: its extent in the face's own axes, minus the border band,
    ``Offset`` in front of it, facing the room."""
    index = face_index(subs[0]) if subs else None
    shape = global_shape(base)
    if index is None or index >= len(shape.Faces):
        raise ValueError(f"Grid target '{obj.Label}' ({obj.Surface}): select one planar face "
                         f"of '{base.Label}' as its Base (got {list(subs) or 'the whole object'})")
    face = shape.Faces[index]
    if not is_planar(face):
        raise ValueError(f"Grid target '{obj.Label}': '{base.Label}.{subs[0]}' is not planar; "
                         "wall, ceiling and floor grids need a planar face")
    normal = room_side_normal(base, face)
    u, v = face_axes(normal)
    origin = face.Vertexes[0].Point
    us = [(p - origin).dot(u) for p in _face_points(face)]
    vs = [(p - origin).dot(v) for p in _face_points(face)]
    band = float(obj.WallBand)
    u0, u1, v0, v1 = min(us) + band, max(us) - band, min(vs) + band, max(vs) - band
    if u1 - u0 <= 1.0 or v1 - v0 <= 1.0:
        raise _no_area(obj, base, max(us) - min(us), max(vs) - min(vs), "border band")
    nu, nv, p_mm = _cells(obj, u1 - u0, v1 - v0)
    corner = origin + u * u0 + v * v0 + normal * float(obj.Offset)
    return GridRect(corner, u * (u1 - u0), v * (v1 - v0), nu, nv, p_mm)


def grid_rectangle(obj: Any) -> GridRect:
    """The calculation grid of a grid target (global, mm). Raises ValueError with the reason."""
    base, subs = _base_of(obj)
    surface = getattr(obj, "Surface", "Work plane")  # older files: migrated on restore
    if surface == "Work plane":
        return _horizontal_grid(obj, base, subs, float(obj.WorkplaneHeight))
    if surface == "Floor" and not subs:
        return _horizontal_grid(obj, base, subs, float(obj.Offset))
    return _surface_grid(obj, base, subs)


def check(obj: Any) -> List[tuple]:
    """Missing references, empty grids and absurd values: list of (level, text)."""
    problems: List[tuple] = []
    name = obj.Label
    if obj.TargetType == "Faces":
        if not obj.References:
            problems.append(("error", f"Target '{name}' has no faces: select faces and "
                                      "recreate it, or set its References"))
        else:
            try:
                referenced_faces(obj.References)
            except ValueError as exc:
                problems.append(("error", f"Target '{name}': {exc}"))
        return problems
    try:
        rect = grid_rectangle(obj)
    except ValueError as exc:
        return [("error", str(exc))]
    if rect.nu * rect.nv > 250000:
        problems.append(("warning", f"Grid target '{name}' has {rect.nu * rect.nv} cells; "
                                    "each gets few photons"))
    if getattr(obj, "Surface", "Work plane") != "Work plane":
        return problems
    height = float(obj.WorkplaneHeight)
    if height < 0.0 or height > 5000.0:
        problems.append(("warning", f"Grid target '{name}': work-plane height "
                                    f"{height / 1000:g} m is unusual (EN 12464-1: 0.80 m)"))
    base = obj.Base[0]
    if ifc_type(base) == "space" and rect.corner.z >= base.Shape.BoundBox.ZMax:
        problems.append(("error", f"Grid target '{name}' lies above the space '{base.Label}'"))
    return problems
