# SPDX-License-Identifier: LGPL-2.1-or-later
"""FreeCAD module "Lighting": GUI initialisation.

The workbench class is defined here; commands and task panels are imported in ``Initialize``
(first activation), so FreeCAD's start-up stays fast. The document observer that gives
Lighting objects their view providers (lighting/viewproviders/observer.py) is installed at
start-up, so objects made by scripts and files opened before the first activation get them.
FreeCAD runs this file with exec() and separate globals/locals: module-level names are not
visible inside the class, hence the imports inside the methods."""


class LightingWorkbench(Workbench):  # noqa: F821 - FreeCAD provides Workbench here
    """Architectural lighting: luminaires, targets, analysis with the lightsolver engine."""

    MenuText = "Lighting"
    ToolTip = "Illuminance analysis of architectural models (photon tracing, EN 12464-1)"

    def __init__(self):
        from lighting.viewproviders.base import icon_path

        self.__class__.Icon = icon_path("Lighting_Workbench")

    def Initialize(self):
        from lighting.commands import commands

        commands.register()
        for title, names in commands.TOOLBARS:
            self.appendToolbar(title, names)
        self.appendMenu("Lighting", commands.MODEL_COMMANDS + ["Separator"] + commands.RUN_COMMANDS
                        + ["Separator"] + commands.EXCLUSION_COMMANDS)

    def Activated(self):
        pass

    def Deactivated(self):
        pass

    def ContextMenu(self, recipient):
        from lighting.commands import commands

        if recipient == "Tree":
            self.appendContextMenu("Lighting", commands.RUN_COMMANDS)
        # On any selected model object, in the tree or the 3D view.
        self.appendContextMenu("", commands.EXCLUSION_COMMANDS)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


Gui.addWorkbench(LightingWorkbench())  # noqa: F821 - FreeCAD provides Gui here

import lighting.viewproviders.observer as _lighting_observer  # noqa: E402

_lighting_observer.install()
