# SPDX-License-Identifier: LGPL-2.1-or-later
"""Observer: an eye in the room for discomfort glare (UGR, CIE 117; docs/glare.md).

Its Placement is the eye: ``Placement.Base`` the eye position, the line of sight along the
local +X axis, up along local +Z (usually level: a seated or standing person looking across
the room). The solver traces the indirect illuminance at the eye in the view direction
(background luminance L_b = E/π, with its interval) and reports the UGR of the scene's
luminaires with an interval and, with ``UgrMax``, a verdict (pass when the whole interval is
at or below the limit).

In grid mode (``GridMode``) it is an observer grid (docs/glare.md, "Observer grids"): eyes at
the cell centres of a GridLength x GridWidth rectangle in the eye's level plane, starting at
the Placement and spanning its local +X and +Y, each looking every ``ViewStep`` degrees around
(90: CIE's crosswise and endwise directions); the solver reports the maximum UGR with an
interval that holds for the maximum, and where it is."""
from __future__ import annotations

import math
from typing import Any, Dict, List

import FreeCAD

from lighting import standards
from lighting.objects.base import BaseProxy, Prop
from lighting.units import MM_TO_M, vec_m

TYPE = "Lighting::Observer"
#: Eye heights by convention (CIE 117 / EN 12464-1 practice).
EYE_HEIGHT_M = {"Seated": 1.2, "Standing": 1.7}
LOCAL_VIEW = FreeCAD.Vector(1, 0, 0)
LOCAL_UP = FreeCAD.Vector(0, 0, 1)


class Observer(BaseProxy):
    """An eye with a line of sight; the symbol shows the eye, the view and the field."""

    TYPE = TYPE
    PROPERTIES = {
        "UgrMax": Prop("App::PropertyFloat", "Requirements",
                       "UGR limit R_UGL (EN 12464-1; e.g. 19 for offices); 0 = no requirement",
                       0.0),
        "Activity": Prop("App::PropertyEnumeration", "Requirements",
                         "EN 12464-1 preset of UgrMax (the requirements table's UGR_L)",
                         standards.CUSTOM, items=standards.ACTIVITIES),
        "Posture": Prop("App::PropertyEnumeration", "Observer",
                        "Seated (eye 1.2 m) or standing (1.7 m) above the floor the observer "
                        "is placed on (the eye's height is the Placement's; this records the "
                        "convention used)", "Seated", items=tuple(EYE_HEIGHT_M)),
        "SymbolSize": Prop("App::PropertyLength", "Display", "Size of the eye symbol", 300.0),
        "GridMode": Prop("App::PropertyBool", "Grid",
                         "An observer grid: eyes over a rectangle, looking every ViewStep "
                         "degrees; the maximum UGR is reported", False),
        "GridLength": Prop("App::PropertyLength", "Grid",
                           "Rectangle side along the local +X axis from the Placement", 2000.0),
        "GridWidth": Prop("App::PropertyLength", "Grid",
                          "Rectangle side along the local +Y axis from the Placement", 2000.0),
        "GridCellsX": Prop("App::PropertyInteger", "Grid", "Eyes along GridLength", 2),
        "GridCellsY": Prop("App::PropertyInteger", "Grid", "Eyes along GridWidth", 2),
        "ViewStep": Prop("App::PropertyFloat", "Grid",
                         "Degrees between the view directions of every eye (divides 360; 90: "
                         "the two axial directions both ways, 15: a fine scan)", 90.0),
    }

    def execute(self, obj: Any) -> None:
        """The symbol: an eye sphere, the line of sight and the outline of the UGR field
        (about 62 degrees up, 72 to either side: CIE 117's table limits)."""
        import Part

        size = max(float(obj.SymbolSize), 10.0)
        shapes = [Part.makeSphere(size * 0.12)]
        shapes.append(Part.makeLine(FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(size * 2.0, 0, 0)))
        # Field outline at one symbol length: T/R <= 3 sideways, H/R <= 1.9 up, the sight line.
        r = size
        corners = [FreeCAD.Vector(r, -3.0 * r, 0), FreeCAD.Vector(r, -3.0 * r, 1.9 * r),
                   FreeCAD.Vector(r, 3.0 * r, 1.9 * r), FreeCAD.Vector(r, 3.0 * r, 0)]
        shapes.append(Part.makePolygon(corners + [corners[0]]))
        if getattr(obj, "GridMode", False):  # the rectangle of eyes, in the eye's level plane
            length, width = float(obj.GridLength), float(obj.GridWidth)
            outline = [FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(length, 0, 0),
                       FreeCAD.Vector(length, width, 0), FreeCAD.Vector(0, width, 0)]
            shapes.append(Part.makePolygon(outline + [outline[0]]))
        shape = Part.makeCompound(shapes)
        shape.Placement = obj.Placement
        obj.Shape = shape

    def onChanged(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        """Activity fills UgrMax from the requirements table; typing a limit makes it Custom."""
        if "Activity" not in obj.PropertiesList or "UgrMax" not in obj.PropertiesList:
            return
        task = standards.task_of(obj.Activity)
        if prop == "Activity" and task is not None and task.ugr_limit:
            if float(obj.UgrMax) != float(task.ugr_limit):
                obj.UgrMax = float(task.ugr_limit)
        elif prop == "UgrMax" and task is not None and float(obj.UgrMax) != float(
                task.ugr_limit or 0.0):
            obj.Activity = standards.CUSTOM


def activity_of(analysis: Any) -> str:
    """The activity a new observer of ``analysis`` takes: the EN 12464-1 preset of its targets
    with the strictest UGR limit (UGR_L), so its verdict states the limit their task has;
    ``standards.CUSTOM`` (no limit: the results say "no limit set") when no target has a
    preset with a UGR limit."""
    from lighting.objects import analysis as analysis_mod

    best, limit = standards.CUSTOM, math.inf
    for target in analysis_mod.targets(analysis) if analysis is not None else []:
        activity = getattr(target, "Activity", standards.CUSTOM)
        task = standards.task_of(activity)
        if task is not None and task.ugr_limit and float(task.ugr_limit) < limit:
            best, limit = activity, float(task.ugr_limit)
    return best


def view_direction(obj: Any) -> FreeCAD.Vector:
    """The global line of sight (unit)."""
    return obj.getGlobalPlacement().Rotation.multVec(LOCAL_VIEW).normalize()


def up_direction(obj: Any) -> FreeCAD.Vector:
    """The global up of the eye (unit)."""
    return obj.getGlobalPlacement().Rotation.multVec(LOCAL_UP).normalize()


def grid_entry(obj: Any) -> Dict[str, Any]:
    """An observer in grid mode as an ``observer_grid`` entry (docs/scene-format.md)."""
    placement = obj.getGlobalPlacement()
    edge1 = placement.Rotation.multVec(FreeCAD.Vector(1, 0, 0)) * float(obj.GridLength)
    edge2 = placement.Rotation.multVec(FreeCAD.Vector(0, 1, 0)) * float(obj.GridWidth)
    up = up_direction(obj)
    return {"name": obj.Name, "type": "observer_grid", "corner": vec_m(placement.Base),
            "edge1": vec_m(edge1), "edge2": vec_m(edge2),
            "cells": [int(obj.GridCellsX), int(obj.GridCellsY)],
            "view_step_deg": float(obj.ViewStep), "up": [up.x, up.y, up.z]}


def fit_grid(obj: Any, bound_box: Any, margin_m: float = 0.5) -> None:
    """Grid mode over ``bound_box`` (a selected face's or the room's, mm) less ``margin_m``
    on each side (EN 12464-1's wall band), at the eye's height, level and along the axes."""
    margin = margin_m / MM_TO_M
    length = max(bound_box.XLength - 2 * margin, 1.0)
    width = max(bound_box.YLength - 2 * margin, 1.0)
    base = FreeCAD.Vector(bound_box.XMin + 0.5 * (bound_box.XLength - length),
                          bound_box.YMin + 0.5 * (bound_box.YLength - width),
                          obj.Placement.Base.z)
    obj.Placement = FreeCAD.Placement(base, FreeCAD.Rotation())
    obj.GridLength, obj.GridWidth = length, width
    obj.GridMode = True


def scene_entry(obj: Any) -> Dict[str, Any]:
    """The observer as a ``targets[]`` entry of docs/scene-format.md (metres): an ``observer``,
    or in grid mode an ``observer_grid``."""
    if getattr(obj, "GridMode", False):
        entry = grid_entry(obj)
        if float(obj.UgrMax) > 0.0:
            entry["requirements"] = {"ugr_max": float(obj.UgrMax)}
        return entry
    view, up = view_direction(obj), up_direction(obj)
    entry: Dict[str, Any] = {"name": obj.Name, "type": "observer",
                             "position": vec_m(obj.getGlobalPlacement().Base),
                             "view_direction": [view.x, view.y, view.z],
                             "up": [up.x, up.y, up.z]}
    if float(obj.UgrMax) > 0.0:
        entry["requirements"] = {"ugr_max": float(obj.UgrMax)}
    return entry


def check(obj: Any) -> List[tuple]:
    """What only the document can judge: an eye below the floor is suspicious, a limit out
    of UGR's range an error (the solver checks the rest)."""
    problems: List[tuple] = []
    ugr = float(obj.UgrMax)
    if ugr < 0.0 or ugr > 40.0:
        problems.append(("error", f"Observer '{obj.Label}': UgrMax must be in (0, 40] or 0 for "
                                  f"none (got {ugr:g})"))
    height = obj.getGlobalPlacement().Base.z * MM_TO_M
    if height < 0.5:
        problems.append(("warning", f"Observer '{obj.Label}': the eye is {height:.2f} m high; "
                                    "UGR is defined for eyes at 1.2 m (seated) or 1.7 m "
                                    "(standing) above the floor"))
    return problems
