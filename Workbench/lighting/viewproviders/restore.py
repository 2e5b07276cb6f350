# SPDX-License-Identifier: LGPL-2.1-or-later
"""Documents saved by freecadcmd (scripts, Examples/office.py) have no GuiDocument.xml.
FreeCAD 0.20's GUI then opens C++ features (Part::Box, Part::MultiFuse, Mesh::Feature...)
hidden, although their saved ``Visibility`` is true, and Arch objects without their Arch view
providers. Visibility no longer changes the calculation (only ``LightingExclude`` leaves an
object out, export/collect.py), so this is about what the user sees: the desk and the cabinet
of the example would be missing from the view while they are lit in the scene. This
re-applies the visibility stored in Document.xml, once per opened file, and gives Arch objects
their view providers, for documents that contain a Lighting analysis."""
from __future__ import annotations

import xml.etree.ElementTree as ElementTree
import zipfile
from typing import Any, Dict

import FreeCAD

_done: set = set()


def saved_visibility(path: str) -> Dict[str, bool]:
    """Object name -> saved App Visibility, or {} when the file has a GuiDocument.xml."""
    try:
        with zipfile.ZipFile(path) as archive:
            if "GuiDocument.xml" in archive.namelist():
                return {}
            root = ElementTree.fromstring(archive.read("Document.xml"))
    except (OSError, KeyError, zipfile.BadZipFile, ElementTree.ParseError):
        return {}
    result: Dict[str, bool] = {}
    data = root.find("ObjectData")
    for element in (data if data is not None else []):
        name = element.get("name")
        for prop in element.iter("Property"):
            if prop.get("name") == "Visibility":
                flag = prop.find("Bool")
                if name and flag is not None:
                    result[name] = flag.get("value") == "true"
                break
    return result


def fix_headless_visibility(doc: Any) -> int:
    """Apply the saved visibility to the view objects; returns how many changed."""
    if doc is None or not doc.FileName or not FreeCAD.GuiUp:
        return 0
    key = (doc.Name, doc.FileName)
    if key in _done:
        return 0
    _done.add(key)
    changed = 0
    for name, visible in saved_visibility(doc.FileName).items():
        obj = doc.getObject(name)
        vobj = getattr(obj, "ViewObject", None) if obj is not None else None
        if vobj is not None and bool(vobj.Visibility) != visible:
            vobj.Visibility = visible
            changed += 1
    if changed:
        FreeCAD.Console.PrintLog(f"Lighting: restored the visibility of {changed} object(s) "
                                 f"of {doc.FileName} (saved without GUI data)\n")
    return changed


def attach_arch_view_providers(doc: Any) -> int:
    """Give Arch objects created headless (no view provider proxy) their Arch view provider,
    found by Arch's naming convention (``ArchWall._Wall`` -> ``ArchWall._ViewProviderWall``),
    so walls, windows and spaces look as usual (a space without it is an opaque box)."""
    if doc is None or not FreeCAD.GuiUp:
        return 0
    import importlib

    attached = 0
    for obj in doc.Objects:
        proxy, vobj = getattr(obj, "Proxy", None), getattr(obj, "ViewObject", None)
        if proxy is None or vobj is None or isinstance(proxy, (int, str)):
            continue
        current = getattr(vobj, "Proxy", None)
        if current is not None and not isinstance(current, (int, float, str)):
            continue
        module_name = type(proxy).__module__
        if not module_name.startswith("Arch"):
            continue
        try:
            module = importlib.import_module(module_name)
            cls = getattr(module, "_ViewProvider" + type(proxy).__name__.lstrip("_"), None)
            if cls is not None:
                _attach_late(cls, vobj)
                attached += 1
        except Exception as exc:  # noqa: BLE001 - cosmetic: keep the plain view provider
            FreeCAD.Console.PrintLog(f"Lighting: no Arch view provider for {obj.Name}: {exc}\n")
    return attached


def _attach_late(cls: Any, vobj: Any) -> None:
    """``cls(vobj)`` on a view object that is already attached: FreeCAD does not call the new
    proxy's ``attach`` then, and Arch's ``__init__`` sets view properties whose ``onChanged``
    needs the nodes ``attach`` makes (an ArchSpace printed "'_ViewProviderSpace' object has no
    attribute 'fmat'" on every colour change). So: construct with onChanged muted, attach,
    then let the proxy see its colour and transparency."""
    proxy = cls.__new__(cls)
    proxy.onChanged = lambda *args: None  # instance attribute: shadows the method meanwhile
    try:
        cls.__init__(proxy, vobj)
    finally:
        del proxy.onChanged
    if hasattr(proxy, "attach"):
        proxy.attach(vobj)
    for prop in ("ShapeColor", "Transparency", "LineColor", "Visibility"):
        if prop in vobj.PropertiesList:
            try:
                proxy.onChanged(vobj, prop)
            except Exception:  # noqa: BLE001 - cosmetic
                pass


def after_restore(doc: Any) -> None:
    """Everything done once a document with a Lighting analysis is open in the GUI."""
    fix_headless_visibility(doc)
    attach_arch_view_providers(doc)
