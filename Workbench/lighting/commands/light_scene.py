# SPDX-License-Identifier: LGPL-2.1-or-later
"""Command "Light scene": a dimming level per control group of the active analysis, shown by
rescaling one trace (objects/light_scene.py); its levels are edited in the analysis panel."""
from __future__ import annotations

import FreeCAD

from lighting.commands import commands


class CommandLightScene(commands.BaseCommand):
    NAME, ICON = "Lighting_LightScene", "Lighting_LightScene"
    MENU = "Light scene"
    TIP = ("A light scene of the active analysis: a dimming level per control group (the "
           "luminaires' ControlGroup). Switching scenes or changing levels rescales one run "
           "(traced with contributions), no tracing")

    def IsActive(self) -> bool:  # noqa: N802
        return commands.active_analysis() is not None

    def Activated(self) -> None:  # noqa: N802
        analysis = commands.active_analysis()
        count = len(commands.light_scene_mod.scenes(analysis)) + 1
        commands._run_transaction("Create light scene", [
            f"lighting.make_light_scene({commands._analysis_arg()}, 'Light scene {count}')"])
        FreeCAD.Console.PrintMessage(
            "Lighting: light scene made; set its levels in the analysis panel (Light scenes). "
            "Run once with contributions, then switching scenes needs no tracing\n")


ALL = (CommandLightScene,)
