# SPDX-License-Identifier: LGPL-2.1-or-later
"""Commands "Exclude from lighting" and "Include in lighting" on the selected objects.

Hiding an object is a viewing choice and leaves it in the calculation; these commands are
how a model object (a ceiling to look into the room, scaffolding geometry, a second design
option) is left out of it or taken back. They set the object's ``LightingExclude`` property
(export/collect.py), which is saved in the file, shown in the property editor under
"Lighting", undoable (one step per command) and available to scripts as
``lighting.exclude(objects, excluded)``. Excluding a group, App::Part or building part leaves
out everything in it."""
from __future__ import annotations

from typing import Any, Dict, List

import FreeCAD
import FreeCADGui

from lighting.export import collect
from lighting.objects.base import is_lighting_object
from lighting.viewproviders.base import icon_path


def _candidates() -> List[Any]:
    """Selected objects that can be excluded (Lighting objects cannot)."""
    return [o for o in FreeCADGui.Selection.getSelection() if not is_lighting_object(o)]


class _ExclusionCommand:
    """Sets LightingExclude of the selection to EXCLUDE."""

    NAME = ""
    ICON = "Lighting_Workbench"
    MENU = ""
    TIP = ""
    EXCLUDE = True

    def GetResources(self) -> Dict[str, str]:  # noqa: N802 (FreeCAD API name)
        return {"Pixmap": icon_path(self.ICON), "MenuText": self.MENU,
                "ToolTip": self.TIP}

    def IsActive(self) -> bool:  # noqa: N802
        """Active when some selected object would change."""
        if FreeCAD.ActiveDocument is None:
            return False
        return any(collect.is_excluded_itself(o) != self.EXCLUDE for o in _candidates())

    def Activated(self) -> None:  # noqa: N802
        objects = [o for o in _candidates() if collect.is_excluded_itself(o) != self.EXCLUDE]
        if not objects:
            return
        names = ", ".join(f"FreeCAD.ActiveDocument.getObject('{o.Name}')" for o in objects)
        FreeCADGui.addModule("lighting")
        # lighting.exclude makes the one undo step itself.
        FreeCADGui.doCommand(f"lighting.exclude([{names}], {self.EXCLUDE})")
        verb = "left out of" if self.EXCLUDE else "taken back into"
        labels = ", ".join(f"'{o.Label}'" for o in objects)
        FreeCAD.Console.PrintMessage(f"Lighting: {labels} {verb} the lighting model\n")


class CommandExclude(_ExclusionCommand):
    NAME, ICON = "Lighting_Exclude", "Lighting_Exclude"
    MENU = "Exclude from lighting"
    TIP = ("Leave the selected objects out of the lighting calculation (hidden objects stay "
           "in: hiding is only a view). Sets their LightingExclude property; undoable")
    EXCLUDE = True


class CommandInclude(_ExclusionCommand):
    NAME, ICON = "Lighting_Include", "Lighting_Include"
    MENU = "Include in lighting"
    TIP = "Take the selected excluded objects back into the lighting calculation"
    EXCLUDE = False


ALL = (CommandExclude, CommandInclude)
NAMES = [cls.NAME for cls in ALL]
