# SPDX-License-Identifier: LGPL-2.1-or-later
"""Where luminaires go by default (millimetres): the room part of a ceiling face, its frame,
and the ceiling over the middle of the model.

A ceiling slab usually spans the walls it rests on (Arch slabs do), so its underside is
larger than the room: :func:`room_region` cuts the walls' footprints out of the face, and
margins and centres are then measured from the walls, as a designer means them. App code:
used by the Luminaire and Luminaire layout commands and by ``lighting.add_luminaire_layout``."""
from __future__ import annotations

from typing import Any, List, NamedTuple, Optional, Tuple

import FreeCAD

from lighting.geometry import face_normal, global_shape, is_planar

V = FreeCAD.Vector
#: Default distance of a luminaire from the face it is put on (its emitting side).
MOUNTING_OFFSET_MM = 50.0
#: A face is "horizontal" when its normal is within this of the vertical (cosine).
HORIZONTAL_COS = 0.99
#: How far under a face the walls' footprints are taken (they touch the face there).
FOOTPRINT_DEPTH_MM = 1.0


class Frame(NamedTuple):
    """A planar face's layout frame: ``origin`` on the plane, unit axes ``x`` and ``y`` in
    it, outward unit ``normal``; the face's extent along the axes is u0..u1, v0..v1 (mm)."""

    origin: FreeCAD.Vector
    x: FreeCAD.Vector
    y: FreeCAD.Vector
    normal: FreeCAD.Vector
    u0: float
    u1: float
    v0: float
    v1: float

    def point(self, u: float, v: float) -> FreeCAD.Vector:
        """The plane's point at frame coordinates (u, v)."""
        return self.origin + self.x * u + self.y * v


def _unit(vector: FreeCAD.Vector) -> FreeCAD.Vector:
    out = V(vector)
    return out.normalize() if out.Length > 0 else out


def face_frame(face: Any) -> Frame:
    """The frame of a planar face: x along the global X axis projected into the plane (global
    Y for faces facing along X), y in the plane towards global +Y (or +Z on walls)."""
    if not is_planar(face):
        raise ValueError("the face must be planar")
    normal = face_normal(face)
    ref = V(0, 1, 0) if abs(normal.x) > HORIZONTAL_COS else V(1, 0, 0)
    x = _unit(ref - normal * ref.dot(normal))
    y = _unit(normal.cross(x))
    up = V(0, 1, 0) if abs(normal.z) > 0.5 else V(0, 0, 1)
    if y.dot(up) < 0:
        y = y * -1.0
    origin = face.Vertexes[0].Point
    points = [p for w in face.Wires for p in w.discretize(Deflection=1.0)]
    us = [(p - origin).dot(x) for p in points]
    vs = [(p - origin).dot(y) for p in points]
    return Frame(origin, x, y, normal, min(us), max(us), min(vs), max(vs))


def aim_for_normal(normal: FreeCAD.Vector) -> FreeCAD.Vector:
    """The aim of a luminaire mounted on a face: away from a ceiling or a wall (along the
    outward normal, into the room), down onto a floor-like face it hangs above."""
    return normal * -1.0 if normal.z > 0.5 else V(normal)


def _footprints(face: Any, solids: List[Any]) -> List[Any]:
    """Cross-sections of ``solids`` just in front of ``face`` (where walls touch it), moved
    onto the face's plane."""
    import Part

    normal = face_normal(face)
    on_plane = face.Vertexes[0].Point
    depth = on_plane.dot(normal) + FOOTPRINT_DEPTH_MM
    box = face.BoundBox
    box.enlarge(2.0 * FOOTPRINT_DEPTH_MM)
    found = []
    for solid in solids:
        if not solid.BoundBox.intersect(box):
            continue
        wires = [w for w in solid.slice(normal, depth) if w.isClosed()]
        if not wires:
            continue
        # A wall ring slices into an outer and an inner wire: nested wires make holes.
        section = Part.makeFace(wires, "Part::FaceMakerBullseye")
        section.translate(normal * -FOOTPRINT_DEPTH_MM)
        found.extend(section.Faces)
    return found


def room_region(face: Any, solids: List[Any]) -> Any:
    """The part of ``face`` not covered by the footprints of ``solids`` touching it (the room
    under a slab that spans its walls): the outline of the largest piece, or the face itself
    when nothing touches it or the boolean fails."""
    try:
        cuts = _footprints(face, solids)
        if not cuts:
            return face
        pieces = face.cut(cuts).Faces
    except Exception:  # noqa: BLE001 - OCC booleans can fail; the whole face is a fair answer
        return face
    if not pieces:
        return face
    # Islands inside the room (desk legs on a floor, a column) are not walls: keep the
    # room's outline only, so they do not move its centre or its field.
    import Part

    return Part.Face(max(pieces, key=lambda f: f.Area).OuterWire)


def model_solids(doc: Any, leave_out: Tuple[str, ...] = ()) -> List[Any]:
    """Solids of the exported objects (global coordinates), except those named."""
    from lighting.export import collect

    solids = []
    for obj in collect.exported_objects(doc):
        if obj.Name in leave_out or collect.is_mesh(obj):
            continue
        try:
            solids.extend(global_shape(obj).Solids)
        except Exception:  # noqa: BLE001 - a broken object does not stop the placement
            continue
    return solids


def inside_point(face: Any, point: FreeCAD.Vector) -> FreeCAD.Vector:
    """``point`` if it lies on the face, else the face's nearest point (L-shaped rooms)."""
    import Part

    if face.isInside(point, 0.01, True):
        return point
    return face.distToShape(Part.Vertex(point))[1][0][0]


def face_centre(face: Any) -> FreeCAD.Vector:
    """The centre of mass of a face, moved onto the face when it lies outside."""
    return inside_point(face, face.CenterOfMass)


def spot_on_face(face: Any, solids: List[Any],
                 offset_mm: float = MOUNTING_OFFSET_MM) -> Tuple[FreeCAD.Vector, FreeCAD.Vector]:
    """(position, aim) of one luminaire on a face: the centre of its room region,
    ``offset_mm`` in front of it, aimed into the room (:func:`aim_for_normal`); a floor-like
    face gets it at the ceiling above, when one is found, else 2.5 m above."""
    normal = face_normal(face)
    region = room_region(face, solids) if is_planar(face) else face
    centre = face_centre(region)
    if normal.z > 0.5:
        ceiling = ceiling_above(centre, solids)
        height = (ceiling - centre.z - offset_mm) if ceiling is not None else 2500.0
        return centre + V(0, 0, height), V(0, 0, -1)
    return centre + normal * offset_mm, aim_for_normal(normal)


def ceiling_above(point: FreeCAD.Vector, solids: List[Any]) -> Optional[float]:
    """Height (z, mm) of the lowest downward-facing horizontal face above ``point`` whose
    outline contains it, or None."""
    best = None
    for face in _downward_faces(solids):
        z = face.Vertexes[0].Point.z
        if z <= point.z or (best is not None and z >= best):
            continue
        if face.isInside(V(point.x, point.y, z), 0.01, True):
            best = z
    return best


def floor_below(point: FreeCAD.Vector, solids: List[Any]) -> Optional[float]:
    """Height (z, mm) of the highest upward-facing horizontal face below ``point`` whose
    outline contains it (the floor an observer stands on), or None."""
    best = None
    for face in (f for s in solids for f in s.Faces
                 if is_planar(f) and face_normal(f).z > HORIZONTAL_COS):
        z = face.Vertexes[0].Point.z
        if z >= point.z or (best is not None and z <= best):
            continue
        if face.isInside(V(point.x, point.y, z), 0.01, True):
            best = z
    return best


def _downward_faces(solids: List[Any]) -> List[Any]:
    return [f for s in solids for f in s.Faces
            if is_planar(f) and face_normal(f).z < -HORIZONTAL_COS]


def ceiling_over_model(solids: List[Any]) -> Optional[Any]:
    """The ceiling over the middle of the model: among the downward-facing horizontal faces
    whose outline contains the centre (x, y) of the solids' bounding box, the one with the
    floor nearest below it, preferring the highest of those (a storey's ceiling, not the
    underside of the floor slab); None without such a face."""
    if not solids:
        return None
    box = FreeCAD.BoundBox()
    for solid in solids:
        box.add(solid.BoundBox)
    cx, cy = box.Center.x, box.Center.y
    candidates = [f for f in _downward_faces(solids)
                  if f.isInside(V(cx, cy, f.Vertexes[0].Point.z), 0.01, True)]
    up_faces = [f for s in solids for f in s.Faces
                if is_planar(f) and face_normal(f).z > HORIZONTAL_COS
                and f.isInside(V(cx, cy, f.Vertexes[0].Point.z), 0.01, True)]
    # A ceiling has a floor under it: the underside of the lowest slab has none.
    with_floor = [f for f in candidates
                  if any(u.Vertexes[0].Point.z < f.Vertexes[0].Point.z for u in up_faces)]
    pool = with_floor or candidates
    return max(pool, key=lambda f: (f.Vertexes[0].Point.z, f.Area)) if pool else None


def default_spot(doc: Any) -> Tuple[FreeCAD.Vector, FreeCAD.Vector, str]:
    """(position, aim, description) of a luminaire added with nothing selected: under the
    ceiling over the middle of the model, at the centre of its room; without a ceiling at
    the model's centre 0.5 m under its top; in an empty document 2.5 m above the origin."""
    solids = model_solids(doc)
    ceiling = ceiling_over_model(solids)
    if ceiling is not None:
        position, aim = spot_on_face(ceiling, solids)
        return position, aim, "at the centre of the room, under the ceiling over the model's middle"
    if solids:
        box = FreeCAD.BoundBox()
        for solid in solids:
            box.add(solid.BoundBox)
        return (V(box.Center.x, box.Center.y, box.ZMax - 500.0), V(0, 0, -1),
                "over the middle of the model, 0.5 m under its top (no ceiling found)")
    return V(0, 0, 2500.0), V(0, 0, -1), "2.5 m above the origin (the document has no geometry)"


def ceiling_link(doc: Any) -> Optional[Tuple[Any, str]]:
    """(object, "FaceN") of the ceiling over the middle of the model (see
    :func:`ceiling_over_model`), for a link property; None without one."""
    from lighting.export import collect

    face = ceiling_over_model(model_solids(doc))
    if face is None:
        return None
    centre = face.CenterOfMass
    for obj in collect.exported_objects(doc):
        if collect.is_mesh(obj):
            continue
        try:
            faces = global_shape(obj).Faces
        except Exception:  # noqa: BLE001
            continue
        for index, candidate in enumerate(faces):
            if (abs(candidate.Area - face.Area) < 1e-6 * max(face.Area, 1.0)
                    and (candidate.CenterOfMass - centre).Length < 1e-6):
                return obj, f"Face{index + 1}"
    return None
