# SPDX-License-Identifier: LGPL-2.1-or-later
"""Command "Sky": daylight through the model's Arch windows (objects/sky.py)."""
from __future__ import annotations

import FreeCAD
import FreeCADGui

from lighting.commands import commands


class CommandSky(commands.BaseCommand):
    NAME, ICON = "Lighting_Sky", "Lighting_Sky"
    MENU = "Sky (daylight)"
    TIP = ("Add a sky: CIE overcast (daylight factors), CIE standard general or Perez sky, "
           "with the site from the document's Arch Site. Every Arch window hosted in a wall "
           "becomes a portal on the wall's inner face (selected faces too), glazed with "
           "tau_v 0.75 double glazing, frame factor 0.8, maintenance 0.9 unless the window's "
           "glass material says otherwise")

    def Activated(self) -> None:  # noqa: N802
        faces = commands._selected_faces()
        lines = [f"_sky = lighting.make_sky(FreeCAD.ActiveDocument, "
                 f"analysis={commands._analysis_arg()})"]
        if faces:
            refs = ", ".join(f"(FreeCAD.ActiveDocument.getObject({o.Name!r}), {subs!r})"
                             for o, subs in faces)
            lines.append(f"_sky.PortalFaces = [{refs}]")
        commands._run_transaction("Create sky", lines)
        from lighting.objects import sky as sky_mod

        made = sky_mod.skies(FreeCAD.ActiveDocument)
        if not made:
            return
        sky = made[-1]
        count = getattr(sky, "PortalCount", 0)
        FreeCAD.Console.PrintMessage(f"Lighting: sky made with {count} portal(s); its site is "
                                     f"{getattr(sky, 'SiteUsed', '')}\n")
        FreeCADGui.Selection.clearSelection()


ALL = (CommandSky,)
