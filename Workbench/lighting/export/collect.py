# SPDX-License-Identifier: LGPL-2.1-or-later
"""Which document objects become scene geometry, and why the others do not.

Exported: objects with faces (Part features, Arch walls, slabs, roofs, windows, stairs,
PartDesign bodies...) and meshes (Mesh::Feature, e.g. furniture), **whether shown or hidden**:
visibility is a viewing choice (hide the ceiling to look into the room), not physics.
Left out: objects explicitly excluded (their ``LightingExclude`` property, or that of a group,
App::Part or building part holding them: :func:`set_excluded`), Lighting objects, containers,
Arch spaces and other non-physical objects, objects without faces, and objects another object
consumes (the ``Base``/``Tool`` of booleans, Arch additions and subtractions, ``Links`` of
compounds...), because the consumer already contains them. :func:`left_out` says which and
why (the Check stage lists it)."""
from __future__ import annotations

from typing import Any, Iterable, List, Optional, Set, Tuple

from lighting.compat import ifc_type, is_group
from lighting.objects.base import is_lighting_object

#: The property that leaves an object (and what it contains) out of the lighting model.
EXCLUDE_PROPERTY = "LightingExclude"
EXCLUDE_DOC = ("Leave this object (and, for a group, App::Part or building part, everything in "
               "it) out of the lighting calculation. Hidden objects stay in: visibility is only "
               "a viewing choice")
#: Property flag Prop_Output: toggling exclusion does not mark the object for recompute.
_PROP_OUTPUT = 8

#: Link properties whose targets are geometry inputs of the object holding them.
CONSUMING_PROPERTIES = ("Base", "Tool", "Shapes", "Additions", "Subtractions", "Links",
                        "Source", "Profile", "Sections", "Spine", "BaseFeature")
#: Link properties that consume their targets only for some object types (a Draft
#: Facebinder's ``Faces`` copies faces and leaves the original in place; Part Thickness
#: hollows its base out).
CONSUMING_BY_TYPE = {"Part::Thickness": ("Faces",)}
#: IFC types that are not physical surfaces.
NON_PHYSICAL_TYPES = {"space", "annotation", "grid", "openingelement", "virtualelement",
                      "spatialzone", "site", "building", "buildingstorey", "project"}
#: Arch proxy types that are not physical surfaces.
NON_PHYSICAL_PROXIES = {"Space", "SectionPlane", "Axis", "AxisSystem", "Grid", "Site",
                        "Building", "Floor", "BuildingPart", "Panel Sheet", "Panel Cut"}


def _linked_objects(value: Any) -> Iterable[Any]:
    """Document objects inside a link property's value (link, list, link-sub tuples)."""
    if value is None:
        return []
    if hasattr(value, "TypeId") and hasattr(value, "Name"):
        return [value]
    found: List[Any] = []
    if isinstance(value, (list, tuple)):
        for item in value:
            if hasattr(item, "TypeId") and hasattr(item, "Name"):
                found.append(item)
            elif isinstance(item, (list, tuple)) and item and hasattr(item[0], "TypeId"):
                found.append(item[0])
    return found


def consumed_names(doc: Any) -> Set[str]:
    """Names of objects that other (non-Lighting) objects use as geometry input."""
    names: Set[str] = set()
    for obj in doc.Objects:
        if is_lighting_object(obj):  # a grid's Base floor is still geometry
            continue
        props = set(obj.PropertiesList)
        for prop in CONSUMING_PROPERTIES + CONSUMING_BY_TYPE.get(obj.TypeId, ()):
            if prop in props:
                try:
                    value = getattr(obj, prop)
                except Exception:  # noqa: BLE001 - unreadable property
                    continue
                names.update(o.Name for o in _linked_objects(value))
    return names


def _body_of(obj: Any) -> Any:
    try:
        parent = obj.getParentGeoFeatureGroup()
    except Exception:  # noqa: BLE001
        return None
    return parent if parent is not None and parent.TypeId == "PartDesign::Body" else None


def _containers(obj: Any) -> List[Any]:
    """Groups, App::Parts and building parts that hold ``obj`` directly."""
    found = []
    try:
        parent = obj.getParentGeoFeatureGroup()
    except Exception:  # noqa: BLE001 - objects without the method
        parent = None
    if parent is not None:
        found.append(parent)
    for holder in getattr(obj, "InList", []):
        if holder is not parent and is_group(holder) and obj in list(getattr(holder, "Group", [])):
            found.append(holder)
    return found


def is_excluded_itself(obj: Any) -> bool:
    """True when the object's own ``LightingExclude`` is set."""
    return EXCLUDE_PROPERTY in getattr(obj, "PropertiesList", ()) and \
        bool(getattr(obj, EXCLUDE_PROPERTY))


def excluded_by(obj: Any) -> Optional[Any]:
    """The object whose ``LightingExclude`` leaves ``obj`` out: itself or a container holding
    it (at any depth); None when it is not excluded."""
    seen: Set[str] = set()
    pending = [obj]
    while pending:
        current = pending.pop()
        if current is None or current.Name in seen:
            continue
        seen.add(current.Name)
        if is_excluded_itself(current):
            return current
        pending.extend(_containers(current))
    return None


def set_excluded(obj: Any, excluded: bool = True) -> bool:
    """Set ``obj.LightingExclude`` (adding the property when missing, in the open undo
    transaction); returns True when the value changed. Lighting objects cannot be excluded."""
    if is_lighting_object(obj):
        raise ValueError(f"'{obj.Label}' is a Lighting object: switch a luminaire off with "
                         "FluxLumen 0, or move it out of the analysis")
    if EXCLUDE_PROPERTY not in obj.PropertiesList:
        if not excluded:
            return False
        obj.addProperty("App::PropertyBool", EXCLUDE_PROPERTY, "Lighting", EXCLUDE_DOC,
                        _PROP_OUTPUT)
    if bool(getattr(obj, EXCLUDE_PROPERTY)) == bool(excluded):
        return False
    setattr(obj, EXCLUDE_PROPERTY, bool(excluded))
    return True


def is_mesh(obj: Any) -> bool:
    """True for Mesh::Feature objects."""
    return obj.isDerivedFrom("Mesh::Feature")


def is_physical(obj: Any) -> bool:
    """True when ``obj`` is the kind of object that can become geometry (exclusion aside)."""
    if is_lighting_object(obj):
        return False
    if obj.TypeId == "PartDesign::Body":
        return True
    if is_group(obj):
        return False
    if ifc_type(obj) in NON_PHYSICAL_TYPES:
        return False
    proxy_type = getattr(getattr(obj, "Proxy", None), "Type", None)
    if isinstance(proxy_type, str) and proxy_type in NON_PHYSICAL_PROXIES:
        return False
    if _body_of(obj) is not None:  # PartDesign features: the body is exported instead
        return False
    if is_mesh(obj):
        return obj.Mesh.CountFacets > 0
    shape = getattr(obj, "Shape", None)
    if shape is None or not hasattr(shape, "Faces"):
        return False
    try:
        return (not shape.isNull()) and len(shape.Faces) > 0
    except Exception:  # noqa: BLE001 - broken shapes are reported by the checks
        return True


def exported_objects(doc: Any) -> List[Any]:
    """The objects that become scene geometry, in document order (hidden ones included)."""
    consumed = consumed_names(doc)
    return [o for o in doc.Objects
            if o.Name not in consumed and is_physical(o) and excluded_by(o) is None]


def is_hidden(obj: Any) -> bool:
    """Hidden in the GUI (or by the App ``Visibility`` headless). Only for telling the user:
    hidden objects are exported like any other."""
    vobj = getattr(obj, "ViewObject", None)
    if vobj is not None:
        return not bool(vobj.Visibility)
    return not bool(getattr(obj, "Visibility", True))


def _why_not_physical(obj: Any) -> Optional[Tuple[str, str]]:
    """(level, reason) for a non-container, non-Lighting object that cannot be geometry."""
    if ifc_type(obj) in NON_PHYSICAL_TYPES or isinstance(
            getattr(getattr(obj, "Proxy", None), "Type", None), str) and \
            obj.Proxy.Type in NON_PHYSICAL_PROXIES:
        kind = ifc_type(obj) or str(obj.Proxy.Type).lower()
        return "info", f"is an Arch {kind}, not a surface"
    if is_mesh(obj):
        return "warning", "is an empty mesh"
    shape = getattr(obj, "Shape", None)
    if shape is None or not hasattr(shape, "Faces"):
        return None  # not a geometric object at all (materials, spreadsheets...)
    if shape.isNull():
        return "warning", "has no shape (recompute it?)"
    return "info", "has no faces (lines or points only)"


def left_out(doc: Any) -> List[Tuple[Any, str, str]]:
    """(object, level, reason) for every object that could be geometry but is not exported:
    excluded explicitly (or with its container), without faces, a space... Objects consumed
    by another one (exported as part of it), containers, Lighting objects and PartDesign
    features (their body is exported) are not listed."""
    consumed = consumed_names(doc)
    found: List[Tuple[Any, str, str]] = []
    for obj in doc.Objects:
        if obj.Name in consumed or is_lighting_object(obj) or _body_of(obj) is not None:
            continue
        if is_group(obj) and obj.TypeId != "PartDesign::Body":
            if is_excluded_itself(obj):
                found.append((obj, "info", "excluded from lighting with everything in it "
                                           "(LightingExclude)"))
            continue
        if is_physical(obj):
            by = excluded_by(obj)
            if by is obj:
                found.append((obj, "info", "excluded from lighting (LightingExclude)"))
            elif by is not None:
                found.append((obj, "info", f"excluded with '{by.Label}' (LightingExclude)"))
            continue
        why = _why_not_physical(obj)
        if why is not None:
            found.append((obj, why[0], why[1]))
    return found
