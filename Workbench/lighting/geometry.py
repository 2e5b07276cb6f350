# SPDX-License-Identifier: LGPL-2.1-or-later
"""Shape helpers shared by the objects, the export and the checks (millimetres)."""
from __future__ import annotations

from typing import Any, List, Optional, Sequence, Tuple

import FreeCAD


def global_placement(obj: Any) -> FreeCAD.Placement:
    """Placement of ``obj`` in global coordinates (through App::Part / building containers)."""
    try:
        return obj.getGlobalPlacement()
    except Exception:  # noqa: BLE001 - objects without a placement
        return getattr(obj, "Placement", FreeCAD.Placement())


def global_shape(obj: Any) -> Any:
    """A copy of ``obj.Shape`` (without cached triangulation) in global coordinates."""
    shape = obj.Shape.copy()
    if "Placement" in obj.PropertiesList:
        local = obj.Placement
        glob = global_placement(obj)
        if glob != local:
            shape.Placement = glob.multiply(local.inverse()).multiply(shape.Placement)
    return shape


def face_index(sub_name: str) -> Optional[int]:
    """Zero-based index of a ``"FaceN"`` sub-element name, else None."""
    if sub_name.startswith("Face") and sub_name[4:].isdigit():
        return int(sub_name[4:]) - 1
    return None


def referenced_faces(links: Sequence[Tuple[Any, Sequence[str]]]) -> List[Tuple[Any, int, Any]]:
    """(object, face index, global face) for each ``FaceN`` of a PropertyLinkSubList value.

    Raises ValueError naming the object when a reference is not a face or no longer exists
    (e.g. the model changed and faces were renumbered)."""
    result: List[Tuple[Any, int, Any]] = []
    for obj, subs in links:
        if obj is None:
            continue
        shape = global_shape(obj)
        for sub in subs:
            index = face_index(sub)
            if index is None:
                raise ValueError(f"'{obj.Label}.{sub}' is not a face")
            if index >= len(shape.Faces):
                raise ValueError(f"'{obj.Label}.{sub}' no longer exists (the object has "
                                 f"{len(shape.Faces)} faces)")
            result.append((obj, index, shape.Faces[index]))
    return result


def face_normal(face: Any) -> FreeCAD.Vector:
    """Outward normal of a face at the middle of its parameter range (orientation-aware)."""
    u0, u1, v0, v1 = face.ParameterRange
    normal = face.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1))
    return normal.normalize() if normal.Length > 0 else normal


def is_planar(face: Any) -> bool:
    """True when the face lies in a plane."""
    try:
        return face.Surface.TypeId == "Part::GeomPlane" or bool(face.isPlanar())
    except Exception:  # noqa: BLE001 - isPlanar is missing on some versions
        return face.Surface.TypeId == "Part::GeomPlane"


def offset_for_display(face: Any, distance_mm: float) -> Any:
    """A copy of a face moved along its normal (planar faces), to draw it over its parent
    without z-fighting. Curved faces are returned unchanged."""
    copy = face.copy()
    if is_planar(face):
        copy.translate(face_normal(face) * distance_mm)
    return copy
