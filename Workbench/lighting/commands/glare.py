# SPDX-License-Identifier: LGPL-2.1-or-later
"""Command "Observer": an eye for discomfort glare (UGR), seated by default, placed at the
selected point or over the selected floor face, else at the middle of the room; it looks
level, along +X (turn it with its Placement). Command "Observer grid": seated eyes over the
selected floor face (else the model), each looking every 90 degrees; the maximum UGR is
reported (docs/glare.md, "Observer grids")."""
from __future__ import annotations

from typing import Any, Tuple

import FreeCAD
import FreeCADGui

from lighting.commands import commands


def _eye_spot() -> Tuple[Any, str]:
    """(eye position mm, description) from the selection or the room under the model."""
    from lighting import placement
    from lighting.objects.observer import EYE_HEIGHT_M

    doc = FreeCAD.ActiveDocument
    eye_mm = EYE_HEIGHT_M["Seated"] * 1000.0
    for sel in FreeCADGui.Selection.getSelectionEx():
        for name, sub in zip(sel.SubElementNames, sel.SubObjects):
            if sub.ShapeType == "Vertex":
                return FreeCAD.Vector(sub.Point), f"at {sel.Object.Label} {name}"
            if sub.ShapeType == "Face":
                centre = placement.face_centre(sub)
                return (FreeCAD.Vector(centre.x, centre.y, centre.z + eye_mm),
                        f"1.2 m above the centre of {sel.Object.Label} {name}")
    position, _, _ = placement.default_spot(doc)
    floor = placement.floor_below(position, placement.model_solids(doc))
    z = (floor if floor is not None else 0.0) + eye_mm
    return FreeCAD.Vector(position.x, position.y, z), "seated (1.2 m) in the middle of the room"


class CommandObserver(commands.BaseCommand):
    NAME, ICON = "Lighting_Observer", "Lighting_Observer"
    MENU = "Observer (glare)"
    TIP = ("An eye for discomfort glare (UGR, CIE 117): seated at 1.2 m over the selected floor "
           "face or point, else in the middle of the room, looking level along +X")

    def Activated(self) -> None:  # noqa: N802
        position, where = _eye_spot()
        commands._run_transaction("Create observer", [
            f"lighting.make_observer(FreeCAD.ActiveDocument, ({position.x / 1000.0:.4f}, "
            f"{position.y / 1000.0:.4f}, {position.z / 1000.0:.4f}), "
            f"analysis={commands._analysis_arg()})"])
        FreeCAD.Console.PrintMessage(f"Lighting: observer placed {where}\n")


def _grid_box() -> Tuple[Any, float, str]:
    """(bound box mm, floor height mm, description): the selected floor face's, else the
    model's with the floor under its middle."""
    from lighting import placement

    for sel in FreeCADGui.Selection.getSelectionEx():
        for name, sub in zip(sel.SubElementNames, sel.SubObjects):
            if sub.ShapeType == "Face":
                return sub.BoundBox, sub.BoundBox.ZMax, f"over {sel.Object.Label} {name}"
    solids = placement.model_solids(FreeCAD.ActiveDocument)
    box = FreeCAD.BoundBox()
    for solid in solids:
        box.add(solid.BoundBox)
    if not box.isValid():
        return FreeCAD.BoundBox(0.0, 0.0, 0.0, 4000.0, 4000.0, 0.0), 0.0, "over 4 x 4 m"
    floor = placement.floor_below(box.Center, solids)
    return box, box.ZMin if floor is None else floor, "over the model"


class CommandObserverGrid(commands.BaseCommand):
    NAME, ICON = "Lighting_ObserverGrid", "Lighting_Observer"
    MENU = "Observer grid (glare)"
    TIP = ("Seated eyes (1.2 m) over the selected floor face, else the model, 0.5 m off its "
           "edges, 2 x 2 positions each looking every 90 degrees (CIE's axial directions): the "
           "maximum UGR with its interval, and where it is")

    def Activated(self) -> None:  # noqa: N802
        from lighting.objects.observer import EYE_HEIGHT_M

        box, floor_mm, where = _grid_box()
        z_m = floor_mm / 1000.0 + EYE_HEIGHT_M["Seated"]
        corners = ", ".join(f"{v:.1f}" for v in (box.XMin, box.YMin, box.ZMin, box.XMax,
                                                  box.YMax, box.ZMax))
        commands._run_transaction("Create observer grid", [
            "from lighting.objects import observer as _observer",
            f"_eyes = lighting.make_observer(FreeCAD.ActiveDocument, ({box.Center.x / 1000.0:.4f},"
            f" {box.Center.y / 1000.0:.4f}, {z_m:.4f}), name='ObserverGrid', "
            f"analysis={commands._analysis_arg()})",
            f"_observer.fit_grid(_eyes, FreeCAD.BoundBox({corners}))"])
        FreeCAD.Console.PrintMessage(f"Lighting: observer grid placed {where}\n")


ALL = (CommandObserver, CommandObserverGrid)
