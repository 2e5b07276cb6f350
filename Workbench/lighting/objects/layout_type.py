# SPDX-License-Identifier: LGPL-2.1-or-later
"""A luminaire layout's type properties on the layout itself.

A layout's members share a hidden template luminaire (the type). So that a user need not
find that template in the tree, the layout shows the template's photometric file, flux and
maintenance factor as its own properties (group "Luminaire type") and keeps the two in step:
an edit on the layout is written to the template (so every member follows), and a change of
the template (the chooser, a script, its own property editor) is read back when the layout
recomputes or its Template link changes.

The mirror is inactive while a document is restored or an undo/redo is replayed: both
restore the template and the layout together, so writing one from the other would only
dirty the document (or fight the undo)."""
from __future__ import annotations

from typing import Any, Dict

from lighting.objects.base import Prop

GROUP = "Luminaire type"

#: Layout property -> template property it mirrors.
MIRRORED: Dict[str, str] = {
    "PhotometricFile": "PhotometricFile",
    "FluxLumen": "FluxLumen",
    "MaintenanceFactor": "MaintenanceFactor",
}

PROPERTIES = {
    "PhotometricFile": Prop("App::PropertyFile", GROUP,
                            "IES LM-63 (.ies) or EULUMDAT (.ldt) file of every luminaire of the "
                            "layout (its template's); setting one makes them photometric"),
    "FluxLumen": Prop("App::PropertyFloat", GROUP,
                      "Initial flux of each luminaire of the layout in lumens (lm), the "
                      "template's; Photometric: 0 = the file's rated lamp lumens"),
    "MaintenanceFactor": Prop("App::PropertyFloat", GROUP,
                              "Maintenance factor (0..1] of every luminaire of the layout, the "
                              "template's; results are maintained values"),
}


def _quiet(obj: Any) -> bool:
    """True while the document restores or replays an undo/redo (no mirroring then)."""
    doc = getattr(obj, "Document", None)
    if doc is None:
        return True
    if getattr(doc, "Restoring", False) or getattr(doc, "Transacting", False):
        return True
    return "Restore" in getattr(obj, "State", [])


def _template(obj: Any) -> Any:
    from lighting.objects.base import proxy_type
    from lighting.objects.luminaire import TYPE

    template = getattr(obj, "Template", None)
    return template if template is not None and proxy_type(template) == TYPE else None


def pull(obj: Any) -> None:
    """Copy the template's values onto the layout (only those that differ)."""
    template = _template(obj)
    if template is None:
        return
    for mine, theirs in MIRRORED.items():
        if mine in obj.PropertiesList and getattr(obj, mine) != getattr(template, theirs):
            setattr(obj, mine, getattr(template, theirs))


def push(obj: Any, prop: str) -> None:
    """Write the layout's ``prop`` to its template (a file makes the template photometric)."""
    template = _template(obj)
    if template is None or prop not in MIRRORED:
        return
    value = getattr(obj, prop)
    if prop == "MaintenanceFactor" and not 0.0 < float(value) <= 1.0:
        import FreeCAD

        FreeCAD.Console.PrintError(
            f"Luminaire layout '{obj.Label}': MaintenanceFactor must be in (0, 1], got "
            f"{value}; kept {template.MaintenanceFactor}\n")
        obj.MaintenanceFactor = template.MaintenanceFactor
        return
    if prop == "FluxLumen" and float(value) < 0.0:
        import FreeCAD

        FreeCAD.Console.PrintError(f"Luminaire layout '{obj.Label}': FluxLumen must be >= 0, "
                                   f"got {value}; kept {template.FluxLumen}\n")
        obj.FluxLumen = template.FluxLumen
        return
    if getattr(template, MIRRORED[prop]) != value:
        setattr(template, MIRRORED[prop], value)
    if prop == "PhotometricFile" and value and template.LuminaireType != "Photometric":
        template.LuminaireType = "Photometric"


def on_changed(obj: Any, prop: str, ready: bool) -> None:
    """The layout's onChanged: push an edited type property, pull on a new Template."""
    if not ready or _quiet(obj):
        return
    if prop == "Template":
        pull(obj)
    elif prop in MIRRORED:
        push(obj, prop)
