# SPDX-License-Identifier: LGPL-2.1-or-later
"""Command "Annual daylight": a year of daylight in the active analysis (objects/annual.py).
Made once per analysis; the command then opens its panel (weather file, Run, the maps)."""
from __future__ import annotations

import FreeCAD
import FreeCADGui

from lighting.commands import commands


class CommandAnnualDaylight(commands.BaseCommand):
    NAME, ICON = "Lighting_AnnualDaylight", "Lighting_AnnualDaylight"
    MENU = "Annual daylight"
    TIP = ("A year of daylight from the site's weather file (.epw): sDA300/50%, ASE1000,250h, "
           "DA300, UDI and EN 17037's levels per grid, with intervals; through the Sky's "
           "windows, on the analysis' grids. Opens its panel (weather file, Run, the maps)")

    def IsActive(self) -> bool:  # noqa: N802
        return commands._doc() is not None and commands.active_analysis() is not None

    def Activated(self) -> None:  # noqa: N802
        from lighting.objects import annual as annual_mod

        analysis = commands.active_analysis()
        found = annual_mod.of_analysis(analysis)
        if not found:
            commands._run_transaction("Create annual daylight", [
                "_annual = lighting.make_annual_daylight("
                f"FreeCAD.ActiveDocument.getObject({analysis.Name!r}))"])
            found = annual_mod.of_analysis(analysis)
            if not found:
                return
            FreeCAD.Console.PrintMessage("Lighting: annual daylight made: choose the site's "
                                         "weather file (.epw) in its panel and press Run\n")
        FreeCADGui.Selection.clearSelection()
        vobj = found[0].ViewObject
        if vobj is not None and vobj.Proxy is not None:
            vobj.Proxy.open_panel(vobj)


ALL = (CommandAnnualDaylight,)
