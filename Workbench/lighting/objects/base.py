# SPDX-License-Identifier: LGPL-2.1-or-later
"""Base of the Lighting document objects: declarative property tables.

Each proxy class lists its properties in ``PROPERTIES`` (name -> :class:`Prop`), the way
FreeCAD-render's ``Render/base.py`` does, instead of ``hasattr`` ladders. The same table adds
missing properties to objects restored from files written by older versions
(:meth:`BaseProxy.onDocumentRestored`), so documents migrate without code per property.

Proxies are App code: they work headless (freecadcmd) and never import GUI code. View
providers live in ``lighting.viewproviders``; the GUI attaches them (viewproviders/observer.py).
"""
from __future__ import annotations

from typing import Any, Dict, NamedTuple, Optional, Sequence

# Property editor modes
NORMAL = 0
READ_ONLY = 1
HIDDEN = 2
# App::PropertyType flag Prop_Output: changes do not touch the object.
PROP_OUTPUT = 8
#: Properties in this group are outputs (see Prop.output).
RESULTS = "Results"


class Prop(NamedTuple):
    """One property of a Lighting object.

    Attributes:
        type: FreeCAD property type, e.g. ``"App::PropertyLength"``.
        group: property editor group.
        doc: tool tip; say the unit when the type does not carry one.
        default: initial value (for enumerations: the selected item).
        mode: NORMAL, READ_ONLY or HIDDEN.
        items: the items of an ``App::PropertyEnumeration``.
        output: an output property (results): changing it does not mark the object for
            recompute.
    """

    type: str
    group: str
    doc: str
    default: Any = None
    mode: int = NORMAL
    items: Sequence[str] = ()
    output: bool = False


class BaseProxy:
    """Common proxy of every Lighting FeaturePython object."""

    #: Stable type name, saved nowhere but used to recognise the object's role.
    TYPE: str = "Lighting::Base"
    #: Declarative property table, completed by subclasses.
    PROPERTIES: Dict[str, Prop] = {}

    def __init__(self, obj: Any) -> None:
        obj.Proxy = self
        self.Type = self.TYPE
        self.ensure_properties(obj, set_defaults=True)

    # -- property table ------------------------------------------------------------------
    @classmethod
    def ensure_properties(cls, obj: Any, set_defaults: bool = False) -> None:
        """Add the properties of ``PROPERTIES`` missing on ``obj``; apply editor modes.

        Defaults are written for newly added properties only, so restored values are kept.
        """
        existing = set(obj.PropertiesList)
        for name, prop in cls.PROPERTIES.items():
            added = name not in existing
            if added:
                obj.addProperty(prop.type, name, prop.group, prop.doc,
                                PROP_OUTPUT if prop.output or prop.group == RESULTS else 0)
            if prop.type == "App::PropertyEnumeration":
                current = getattr(obj, name) if not added else None
                # A restored enumeration with today's items is left alone: writing it again
                # would mark a document just opened as modified.
                if (not added and current in prop.items and
                        list(obj.getEnumerationsOfProperty(name) or []) == list(prop.items)):
                    obj.setEditorMode(name, prop.mode)
                    continue
                setattr(obj, name, list(prop.items))
                if current in prop.items:
                    setattr(obj, name, current)
                elif prop.default is not None:
                    setattr(obj, name, prop.default)
            elif (added or set_defaults) and prop.default is not None:
                setattr(obj, name, prop.default)
            obj.setEditorMode(name, prop.mode)

    # -- FreeCAD hooks -------------------------------------------------------------------
    def onDocumentRestored(self, obj: Any) -> None:  # noqa: N802 (FreeCAD API name)
        """Migrate objects from older files: add new properties with their defaults."""
        self.Type = self.TYPE
        self.ensure_properties(obj)

    def execute(self, obj: Any) -> None:
        """Recompute; subclasses with geometry override this."""

    # FreeCAD 0.20 pickles the proxy with __getstate__, 0.21+ with dumps/loads: keep no state.
    def __getstate__(self) -> Optional[dict]:
        return None

    def __setstate__(self, state: Optional[dict]) -> None:
        return None

    def dumps(self) -> None:
        return None

    def loads(self, state: Optional[dict]) -> None:
        return None


def proxy_type(obj: Any) -> str:
    """The Lighting role of a document object ("" for objects of other workbenches)."""
    proxy = getattr(obj, "Proxy", None)
    if isinstance(proxy, BaseProxy):
        return proxy.TYPE
    value = getattr(proxy, "Type", "")
    return value if isinstance(value, str) and value.startswith("Lighting::") else ""


def is_lighting_object(obj: Any) -> bool:
    """True for luminaires, targets, placement domains and analyses."""
    return bool(proxy_type(obj))


def objects_of_type(doc: Any, type_name: str) -> list:
    """All objects of ``doc`` whose proxy is of the given Lighting type."""
    return [o for o in doc.Objects if proxy_type(o) == type_name]
