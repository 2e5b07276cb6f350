# SPDX-License-Identifier: LGPL-2.1-or-later
"""Command "Choose luminaire data": opens the luminaire chooser (taskpanels/
luminaire_chooser.py) for the selected luminaires, or for a new one."""
from __future__ import annotations

from typing import Any

from lighting.commands import commands as _commands

NAME = "Lighting_ChooseLuminaire"


class CommandChooseLuminaire(_commands.BaseCommand):
    NAME, ICON = NAME, "Lighting_Luminaire"
    MENU = "Choose luminaire data"
    TIP = ("Pick a photometric file (shipped samples or your own folder) with its summary and "
           "polar diagram, and assign it to the selected luminaires or to a new one")

    def Activated(self) -> None:  # noqa: N802 (FreeCAD API name)
        show_chooser()


def show_chooser(luminaire: Any = None) -> Any:
    """Open the chooser (for ``luminaire`` when given: it becomes the selection)."""
    from lighting.taskpanels import luminaire_chooser

    return luminaire_chooser.show(luminaire)
