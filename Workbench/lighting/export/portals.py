# SPDX-License-Identifier: LGPL-2.1-or-later
"""A Sky's portals: the openings of Arch windows hosted in walls, and selected faces.

Each portal is the scene's parallelogram (``corner``, ``edge1``, ``edge2`` in metres,
``edge1 x edge2`` pointing into the room, docs/scene-format.md "sky") on the wall's **inner
face**, with the window's glazing. The opening is the window's hole (Arch's own subtraction
volume, ``getSubVolume``: the base sketch's largest wire extruded along the window's normal);
the wall's faces along that normal are found by lines through the wall just beside the
opening. The room's side is the side of the nearest target of the Sky's analysis (a grid's
centre, a face target's faces), else the centre of the host walls' bounding box: a room's walls
surround it.

The window itself (glass and frame) is left out of the scene when it becomes a portal: the
portal's glazing stands for its glass (tau_v) and frame (frame factor); a frame straddling
the portal's plane would also hide its light behind the frame's faces."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

import FreeCAD

from lighting.compat import get_property, ifc_type
from lighting.units import vec_m

V = FreeCAD.Vector
#: How far beside the opening the wall is probed (mm): past any reveal rounding, inside the
#: wall for any real pier.
PROBE_OFFSET_MM = 30.0


@dataclass
class Portal:
    """One opening: global mm vectors, ``edge1 x edge2`` into the room."""

    source: str  # the window's or face object's Name
    label: str
    corner: Any
    edge1: Any
    edge2: Any
    transmittance: Optional[float] = None  # the window glass' tau_v, None = the Sky's

    def scene_entry(self, glazing: Dict[str, Any]) -> Dict[str, Any]:
        """The scene's portal object (metres)."""
        return {"corner": vec_m(self.corner), "edge1": vec_m(self.edge1),
                "edge2": vec_m(self.edge2), "glazing": glazing}

    @property
    def inward(self) -> Any:
        """Unit normal into the room."""
        return self.edge1.cross(self.edge2).normalize()


@dataclass
class Found:
    """The portals of a Sky, the windows they replace and what went wrong."""

    portals: List[Portal] = field(default_factory=list)
    windows: List[Any] = field(default_factory=list)
    problems: List[Tuple[str, str]] = field(default_factory=list)


def is_window(obj: Any) -> bool:
    """An Arch window (or door: its opening is a portal too when asked for)."""
    proxy_type = getattr(getattr(obj, "Proxy", None), "Type", None)
    return proxy_type == "Window" or ifc_type(obj) == "window"


def hosted_windows(doc: Any) -> List[Any]:
    """Arch windows hosted in some wall, in document order."""
    return [o for o in doc.Objects if is_window(o) and list(get_property(o, "Hosts", []) or [])]


def inside_points(sky: Any) -> List[Any]:
    """Points known to be inside rooms: the centres of the targets of the Sky's analysis (or
    of every target when it is in none)."""
    from lighting.geometry import referenced_faces
    from lighting.objects import target as target_mod
    from lighting.objects.base import objects_of_type

    analysis = next((p for p in sky.InList if hasattr(p, "Group") and
                     getattr(getattr(p, "Proxy", None), "Type", "") == "Lighting::Analysis"),
                    None)
    if analysis is not None:
        from lighting.objects import analysis as analysis_mod

        targets = analysis_mod.targets(analysis)
    else:
        targets = objects_of_type(sky.Document, target_mod.TYPE)
    points = []
    for tgt in targets:
        try:
            if tgt.TargetType == "Grid":
                rect = target_mod.grid_rectangle(tgt)
                points.append(rect.corner + rect.edge1 * 0.5 + rect.edge2 * 0.5)
            else:
                points.extend(face.CenterOfMass for _, _, face in
                              referenced_faces(tgt.References))
        except (ValueError, AttributeError):
            continue
    return points


def _room_side(centre: Any, normal: Any, inside: Sequence[Any], hosts: Sequence[Any]) -> float:
    """+1 when the room lies along ``normal`` from the opening, -1 against it."""
    if inside:
        nearest = min(inside, key=lambda p: (p - centre).Length)
        along = (nearest - centre).dot(normal)
        if abs(along) > 1e-6:
            return 1.0 if along > 0 else -1.0
    boxes = [h.Shape.BoundBox for h in hosts if not h.Shape.isNull()]
    if boxes:
        box = boxes[0]
        for other in boxes[1:]:
            box.add(other)
        along = (box.Center - centre).dot(normal)
        if abs(along) > 1e-6:
            return 1.0 if along > 0 else -1.0
    raise ValueError("cannot tell the room's side: add a target in the room")


def opening_frame(window: Any) -> Tuple[Any, Any, Any, Any, Tuple[float, float, float, float]]:
    """(origin, u, v, n, (u0, u1, v0, v1)): the window's hole as a rectangle in its plane,
    global mm; n along the hole's extrusion, u horizontal where the opening is not."""
    hole = window.Proxy.getSubVolume(window)
    if hole is None or hole.isNull():
        raise ValueError("has no opening (no base sketch)")
    wires = window.Base.Shape.Wires if getattr(window, "Base", None) is not None else []
    if not wires:
        raise ValueError("has no base wire")
    import Part

    largest = max(wires, key=lambda w: w.BoundBox.DiagonalLength)
    normal = Part.Face(largest).normalAt(0, 0)
    custom = get_property(window, "Normal")
    if custom is not None and custom.Length > 0:
        normal = V(custom)
    placement = hole.Placement
    n = placement.Rotation.multVec(normal).normalize()
    up = V(0, 0, 1)
    u = up.cross(n) if abs(n.z) < 0.999 else placement.Rotation.multVec(V(1, 0, 0))
    u = (u - n * u.dot(n)).normalize()
    v = n.cross(u)
    origin = placement.Base
    us = [(p.Point - origin).dot(u) for p in hole.Vertexes]
    vs = [(p.Point - origin).dot(v) for p in hole.Vertexes]
    return origin, u, v, n, (min(us), max(us), min(vs), max(vs))


def wall_span(hosts: Sequence[Any], origin: Any, u: Any, v: Any, n: Any,
              box: Tuple[float, float, float, float], depth_mm: float) -> Tuple[float, float]:
    """(t_min, t_max) along ``n`` from ``origin`` of the host wall beside the opening: lines
    along n just outside each side of the hole, cut by the walls; the span nearest the
    opening's plane."""
    import Part

    u0, u1, v0, v1 = box
    um, vm = 0.5 * (u0 + u1), 0.5 * (v0 + v1)
    probes = [(u1 + PROBE_OFFSET_MM, vm), (u0 - PROBE_OFFSET_MM, vm),
              (um, v1 + PROBE_OFFSET_MM), (um, v0 - PROBE_OFFSET_MM)]
    spans: List[Tuple[float, float]] = []
    for pu, pv in probes:
        point = origin + u * pu + v * pv
        line = Part.LineSegment(point - n * depth_mm, point + n * depth_mm).toShape()
        for host in hosts:
            try:
                cut = host.Shape.common(line)
            except Exception:  # noqa: BLE001 - a broken wall: try the next probe
                continue
            for edge in cut.Edges:
                ts = [(vx.Point - origin).dot(n) for vx in edge.Vertexes]
                if len(ts) == 2 and abs(ts[1] - ts[0]) > 1e-3:
                    spans.append((min(ts), max(ts)))
    if not spans:
        raise ValueError("no wall found around its opening (is it hosted in a wall?)")
    # The span nearest the opening's plane (t = 0): the wall the window sits in.
    return min(spans, key=lambda s: 0.0 if s[0] <= 0.0 <= s[1] else min(abs(s[0]), abs(s[1])))


def window_transmittance(window: Any) -> Optional[float]:
    """tau_v of the window's glass when its material gives one (the workbench's material
    export: an object ``Transmittance``, an Arch material, or the glass part's entry of a
    multi-material); None for the default glass."""
    from lighting.export import materials

    spec = materials.object_property_material(window)
    if spec is None:
        mat = get_property(window, "Material")
        if mat is not None:
            if materials.is_multi_material(mat):
                glass = next((name for name, kind in materials.window_part_kinds(window)
                              if kind == "glass"), None)
                spec = materials.multi_material_entry(mat, glass)
            else:
                spec = materials.arch_material(mat)
    if spec is not None and spec.kind == "glass":
        return float(spec.transmittance)
    return None


def window_portal(window: Any, inside: Sequence[Any]) -> Portal:
    """The portal of one hosted window on its wall's inner face (ValueError saying why not)."""
    hosts = [h for h in list(get_property(window, "Hosts", []) or []) if hasattr(h, "Shape")]
    origin, u, v, n, box = opening_frame(window)
    u0, u1, v0, v1 = box
    depth = max(float(getattr(get_property(window, "HoleDepth", 0.0), "Value", 0.0)), 0.0)
    depth = depth or 2.0 * max(u1 - u0, v1 - v0, 1000.0)
    t0, t1 = wall_span(hosts, origin, u, v, n, box, depth)
    centre = origin + u * (0.5 * (u0 + u1)) + v * (0.5 * (v0 + v1)) + n * (0.5 * (t0 + t1))
    side = _room_side(centre, n, inside, hosts)
    plane = origin + n * (t1 if side > 0 else t0)
    corner = plane + u * u0 + v * v0
    width, height = u * (u1 - u0), v * (v1 - v0)
    # u x v = n: (width, height) points along n, (height, width) against it.
    edge1, edge2 = (width, height) if side > 0 else (height, width)
    return Portal(window.Name, window.Label, corner, edge1, edge2, window_transmittance(window))


def face_portal(obj: Any, index: int, face: Any, inside: Sequence[Any]) -> Portal:
    """A selected planar face as a portal: its bounding rectangle in its plane (a
    non-rectangular face is refused: a portal is a parallelogram)."""
    from lighting.objects.target import face_axes

    if "Plane" not in type(face.Surface).__name__:
        raise ValueError("is not planar")
    from lighting.geometry import face_normal

    n = face_normal(face)
    u, v = face_axes(n)
    centre = face.CenterOfMass
    us = [(p.Point - centre).dot(u) for p in face.Vertexes]
    vs = [(p.Point - centre).dot(v) for p in face.Vertexes]
    area = (max(us) - min(us)) * (max(vs) - min(vs))
    if abs(area - face.Area) > 1e-3 * area:
        raise ValueError("is not a rectangle aligned with its plane's axes; a portal is one "
                         "parallelogram")
    side = _room_side(centre, n, inside, [obj])
    corner = centre + u * min(us) + v * min(vs)
    width, height = u * (max(us) - min(us)), v * (max(vs) - min(vs))
    forward = width.cross(height).dot(n) > 0
    edge1, edge2 = (width, height) if forward == (side > 0) else (height, width)
    return Portal(obj.Name, f"{obj.Label}.Face{index + 1}", corner, edge1, edge2)


def find_portals(sky: Any) -> Found:
    """The Sky's portals: its Windows (all hosted windows when empty) and PortalFaces."""
    from lighting.geometry import referenced_faces

    found = Found()
    inside = inside_points(sky)
    windows = list(sky.Windows) or hosted_windows(sky.Document)
    for window in windows:
        try:
            found.portals.append(window_portal(window, inside))
            found.windows.append(window)
        except (ValueError, AttributeError) as exc:
            found.problems.append(("error", f"Sky '{sky.Label}': window '{window.Label}' {exc}"))
    try:
        faces = referenced_faces(sky.PortalFaces)
    except ValueError as exc:
        found.problems.append(("error", f"Sky '{sky.Label}': {exc}"))
        faces = []
    for obj, index, face in faces:
        try:
            found.portals.append(face_portal(obj, index, face, inside))
        except (ValueError, AttributeError) as exc:
            found.problems.append(("error", f"Sky '{sky.Label}': '{obj.Label}.Face{index + 1}' "
                                            f"{exc}"))
    return found


def portal_shape(portal: Portal) -> Any:
    """The portal drawn: its parallelogram and an arrow into the room."""
    import Part

    c, a, b = portal.corner, portal.edge1, portal.edge2
    face = Part.Face(Part.makePolygon([c, c + a, c + a + b, c + b, c]))
    middle = c + (a + b) * 0.5
    length = 0.25 * min(a.Length, b.Length)
    arrow = Part.makeLine(middle, middle + portal.inward * length)
    return Part.makeCompound([face, arrow])
