# SPDX-License-Identifier: LGPL-2.1-or-later
"""Command "Choose luminaire data": opens the luminaire chooser (taskpanels/
luminaire_chooser.py) for the selected luminaires, or for a new one. commands.py imports this
module at its end, which adds the command to its ALL and MODEL_COMMANDS (toolbar and menu)."""
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


def _extend_lists() -> None:
    """Toolbar and menu place: right after the Luminaire command."""
    if CommandChooseLuminaire not in _commands.ALL:
        _commands.ALL = tuple(_commands.ALL) + (CommandChooseLuminaire,)
    if NAME not in _commands.MODEL_COMMANDS:
        after = _commands.MODEL_COMMANDS.index("Lighting_Luminaire") + 1 \
            if "Lighting_Luminaire" in _commands.MODEL_COMMANDS else len(_commands.MODEL_COMMANDS)
        _commands.MODEL_COMMANDS.insert(after, NAME)


_extend_lists()
