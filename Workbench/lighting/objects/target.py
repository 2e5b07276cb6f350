# SPDX-License-Identifier: LGPL-2.1-or-later
"""Target: where illuminance is reported — selected faces, or a calculation grid over a floor.

Face targets report the mean illuminance on the front (outward) side of exactly the selected
faces. Grid targets are a horizontal rectangle at work-plane height over a floor, slab, space
or floor face, with a wall band left out and the EN 12464-1 spacing unless one is set.
A target is an input only: its results live in the analysis' results object
(objects/results.py)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, List, Tuple

import FreeCAD

from lighting import standards
from lighting.compat import ifc_type
from lighting.geometry import face_index, global_shape, offset_for_display, referenced_faces
from lighting.objects.base import BaseProxy, Prop, READ_ONLY
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
                     "Grid target: floor, slab, Arch space, or one horizontal floor face"),
        "WorkplaneHeight": Prop("App::PropertyLength", "Grid",
                                "Height of the grid above the floor (EN 12464-1: 0.80 m)",
                                standards.WORKPLANE_HEIGHT_M * M_TO_MM),
        "WallBand": Prop("App::PropertyLength", "Grid",
                         "Band along the walls left out of the grid (EN 12464-1: 0.5 m)",
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
    }

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


def grid_rectangle(obj: Any) -> GridRect:
    """The calculation grid of a grid target (global, mm). Raises ValueError with the reason."""
    link = obj.Base
    if not link or link[0] is None:
        raise ValueError(f"Grid target '{obj.Label}' has no Base: select a floor, slab, Arch "
                         "space or floor face")
    base, subs = link[0], tuple(link[1] or ())
    if not hasattr(base, "Shape") or base.Shape.isNull():
        raise ValueError(f"Grid target '{obj.Label}': Base '{base.Label}' has no shape")
    bb, floor_z = _floor_outline(base, subs)
    band = float(obj.WallBand)
    x0, x1 = bb.XMin + band, bb.XMax - band
    y0, y1 = bb.YMin + band, bb.YMax - band
    if x1 - x0 <= 1.0 or y1 - y0 <= 1.0:
        raise ValueError(f"Grid target '{obj.Label}': the wall band of {band / 1000:g} m leaves "
                         f"no area on '{base.Label}' ({bb.XLength / 1000:g} x "
                         f"{bb.YLength / 1000:g} m)")
    nu, nv, p_m = standards.grid_cells((x1 - x0) * MM_TO_M, (y1 - y0) * MM_TO_M,
                                       float(obj.Spacing) * MM_TO_M)
    z = floor_z + float(obj.WorkplaneHeight)
    return GridRect(FreeCAD.Vector(x0, y0, z), FreeCAD.Vector(x1 - x0, 0, 0),
                    FreeCAD.Vector(0, y1 - y0, 0), nu, nv, p_m * M_TO_MM)


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
    height = float(obj.WorkplaneHeight)
    if height < 0.0 or height > 5000.0:
        problems.append(("warning", f"Grid target '{name}': work-plane height "
                                    f"{height / 1000:g} m is unusual (EN 12464-1: 0.80 m)"))
    base = obj.Base[0]
    if ifc_type(base) == "space" and rect.corner.z >= base.Shape.BoundBox.ZMax:
        problems.append(("error", f"Grid target '{name}' lies above the space '{base.Label}'"))
    if rect.nu * rect.nv > 250000:
        problems.append(("warning", f"Grid target '{name}' has {rect.nu * rect.nv} cells; "
                                    "each gets few photons"))
    return problems
