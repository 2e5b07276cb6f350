# SPDX-License-Identifier: LGPL-2.1-or-later
"""Which document objects become scene geometry.

Exported: visible objects with faces (Part features, Arch walls, slabs, roofs, windows,
stairs, PartDesign bodies...) and visible meshes (Mesh::Feature, e.g. furniture).
Left out: Lighting objects, containers (groups, App::Part, building parts), Arch spaces and
other non-physical objects, objects hidden in the tree or inside a hidden App::Part, and
objects another object consumes (the ``Base``/``Tool`` of booleans, Arch additions and
subtractions, ``Links`` of compounds...), because the consumer already contains them and
scripts run headless do not hide them the way GUI commands do."""
from __future__ import annotations

from typing import Any, Iterable, List, Set

from lighting.compat import ifc_type, is_group
from lighting.objects.base import is_lighting_object

#: Link properties whose targets are geometry inputs of the object holding them.
CONSUMING_PROPERTIES = ("Base", "Tool", "Shapes", "Additions", "Subtractions", "Links",
                        "Source", "Profile", "Sections", "Spine", "BaseFeature")
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
        for prop in CONSUMING_PROPERTIES:
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


def is_visible(obj: Any) -> bool:
    """Visible in the GUI (or by the App ``Visibility`` headless), containers included."""
    visible = bool(getattr(obj, "Visibility", True))
    vobj = getattr(obj, "ViewObject", None)
    if vobj is not None:
        visible = bool(vobj.Visibility)
    if not visible:
        return False
    try:
        parent = obj.getParentGeoFeatureGroup()
    except Exception:  # noqa: BLE001
        parent = None
    while parent is not None:
        if not bool(getattr(parent, "Visibility", True)):
            return False
        try:
            parent = parent.getParentGeoFeatureGroup()
        except Exception:  # noqa: BLE001
            break
    return True


def is_mesh(obj: Any) -> bool:
    """True for Mesh::Feature objects."""
    return obj.isDerivedFrom("Mesh::Feature")


def is_physical(obj: Any) -> bool:
    """True when ``obj`` is the kind of object that can become geometry (visibility aside)."""
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
    """The objects that become scene geometry, in document order."""
    consumed = consumed_names(doc)
    return [o for o in doc.Objects
            if o.Name not in consumed and is_physical(o) and is_visible(o)]
