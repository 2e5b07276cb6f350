# SPDX-License-Identifier: LGPL-2.1-or-later
"""Command "Luminaire layout": rows x columns of luminaires over the selected ceiling face
(or, with nothing selected, the ceiling over the middle of the model), created and then
edited live in the layout task panel; OK keeps it as one undo step, Cancel removes it."""
from __future__ import annotations

from typing import Any, List, Optional, Tuple

import FreeCAD
import FreeCADGui
from PySide import QtGui

from lighting.commands.commands import BaseCommand, _analysis_arg, _doc
from lighting.objects import luminaire as luminaire_mod
from lighting.objects import luminaire_layout as layout_mod
from lighting.objects.base import objects_of_type, proxy_type

#: Template properties copied from a luminaire selected together with the face.
COPIED = ("LuminaireType", "FluxLumen", "MaintenanceFactor", "BeamAngle", "FieldAngle",
          "Width", "Length", "PhotometricFile")


def _selection() -> Tuple[Optional[Tuple[Any, str]], Optional[Any]]:
    """(the selected face as (object, "FaceN") or None, a selected luminaire or None)."""
    face, luminaire = None, None
    for sel in FreeCADGui.Selection.getSelectionEx():
        if proxy_type(sel.Object) == luminaire_mod.TYPE:
            luminaire = luminaire or sel.Object
            continue
        names = [n for n in sel.SubElementNames if n.startswith("Face")]
        if names and face is None:
            face = (sel.Object, names[0])
    return face, luminaire


def creation_lines(face: Optional[Tuple[Any, str]], luminaire: Optional[Any],
                   analysis_arg: str) -> List[str]:
    """The console lines that create the layout (and copy a selected luminaire's data)."""
    doc = "FreeCAD.ActiveDocument"
    if face is not None:
        where = f"{doc}.getObject('{face[0].Name}'), {face[1]!r}"
    else:
        where = "None, None, area_m=(4.0, 3.0)"
    lines = [f"_layout = lighting.add_luminaire_layout({doc}, {where}, rows=2, columns=2, "
             f"analysis={analysis_arg})"]
    if luminaire is not None:
        for prop in COPIED:
            value = getattr(luminaire, prop)
            value = float(value) if hasattr(value, "Value") else value
            lines.append(f"_layout.Template.{prop} = {value!r}")
    return lines


class CommandLuminaireLayout(BaseCommand):
    NAME, ICON = "Lighting_LuminaireLayout", "Lighting_LuminaireLayout"
    MENU = "Luminaire layout"
    TIP = ("Rows x columns of luminaires over the selected ceiling face (or the ceiling over "
           "the model), with spacing, margins to the walls, mounting offset and rotation; one "
           "object, editable later (double click). A luminaire selected with the face gives "
           "the type")

    def Activated(self) -> None:  # noqa: N802
        doc = _doc()
        face, luminaire = _selection()
        if face is None:
            from lighting.placement import ceiling_link

            face = ceiling_link(doc)
        doc.openTransaction("Create luminaire layout")
        try:
            before = {o.Name for o in objects_of_type(doc, layout_mod.TYPE)}
            FreeCADGui.addModule("lighting")
            for line in creation_lines(face, luminaire, _analysis_arg()):
                FreeCADGui.doCommand(line)
            FreeCADGui.doCommand("FreeCAD.ActiveDocument.recompute()")
            layout = [o for o in objects_of_type(doc, layout_mod.TYPE) if o.Name not in before][0]
            if face is None:
                self._place_rectangle(doc, layout)
        except Exception as exc:  # noqa: BLE001 - show and undo, never leave half an object
            doc.abortTransaction()
            FreeCAD.Console.PrintError(f"Lighting: Create luminaire layout failed: {exc}\n")
            QtGui.QMessageBox.warning(FreeCADGui.getMainWindow(), "Lighting",
                                      f"Create luminaire layout failed:\n{exc}")
            return
        where = (f"over {face[0].Label} {face[1]}" if face is not None
                 else "over a 4 x 3 m rectangle (no ceiling face selected or found)")
        FreeCAD.Console.PrintMessage(f"Lighting: luminaire layout '{layout.Label}' {where}\n")
        from lighting.taskpanels import sync
        from lighting.taskpanels.layout_panel import LayoutTaskPanel

        FreeCADGui.Control.closeDialog()
        sync.show(LayoutTaskPanel(layout, transaction_open=True))

    @staticmethod
    def _place_rectangle(doc: Any, layout: Any) -> None:
        """A rectangle layout centred where a single luminaire would go."""
        from lighting.placement import default_spot

        position, _, _ = default_spot(doc)
        corner = position + FreeCAD.Vector(-float(layout.AreaLength) / 2.0,
                                           -float(layout.AreaWidth) / 2.0, 0.0)
        FreeCADGui.doCommand(f"_layout.Placement.Base = FreeCAD.Vector({corner.x!r}, "
                             f"{corner.y!r}, {corner.z!r})")
        FreeCADGui.doCommand("_layout.MountingOffset = 0.0")
        FreeCADGui.doCommand("FreeCAD.ActiveDocument.recompute()")
