# SPDX-License-Identifier: LGPL-2.1-or-later
"""Luminaire layout: rows x columns of one luminaire type over a ceiling face or a rectangle
(DIALux's "field arrangement"), one object that stays editable.

The members share a *template* :mod:`luminaire <lighting.objects.luminaire>` (type, flux,
maintenance factor, size, photometric file); the template is the type, not a luminaire in
the room, so it is never exported itself. Members are computed, not stored: changing Rows,
a margin or the template moves or changes all of them. The export turns each member into a
scene luminaire named ``<Layout>_r<row>c<column>`` (:func:`placed_luminaires`).

Frame: over a face (``Base``) the columns run along the face's x axis (global X projected
into it), the rows along its y axis (:func:`lighting.placement.face_frame`); the field is the
face's room region (the walls' footprints cut out, :func:`lighting.placement.room_region`).
Without a face the field is the rectangle ``AreaLength`` x ``AreaWidth`` in the object's XY
plane from its Placement, luminaires hanging below it (along its -Z)."""
from __future__ import annotations

import math
from typing import Any, Dict, List, Optional, Sequence, Tuple

import FreeCAD

from lighting import placement
from lighting.geometry import face_index, global_shape
from lighting.objects import layout_type
from lighting.objects import luminaire as luminaire_mod
from lighting.objects.base import BaseProxy, Prop, READ_ONLY, objects_of_type

TYPE = "Lighting::LuminaireLayout"
V = FreeCAD.Vector
MAX_MEMBERS = 10000


class LuminaireLayout(BaseProxy):
    """An array of luminaires sharing one template luminaire."""

    TYPE = TYPE
    PROPERTIES = {
        "Base": Prop("App::PropertyLinkSub", "Layout",
                     "The planar face the field lies on (a ceiling's underside); empty = the "
                     "rectangle AreaLength x AreaWidth of the Placement"),
        "Template": Prop("App::PropertyLink", "Layout",
                         "Luminaire whose type, flux, maintenance factor, size and photometric "
                         "file every member shares; it is the type, not exported itself"),
        "Columns": Prop("App::PropertyInteger", "Layout",
                        "Luminaires along the field's x axis", 2),
        "Rows": Prop("App::PropertyInteger", "Layout", "Luminaires along the field's y axis", 2),
        "SpacingX": Prop("App::PropertyLength", "Layout",
                         "Distance between columns; 0 = fill the field between the margins", 0.0),
        "SpacingY": Prop("App::PropertyLength", "Layout",
                         "Distance between rows; 0 = fill the field between the margins", 0.0),
        "MarginX": Prop("App::PropertyLength", "Layout",
                        "Distance from the field's edges (the walls) to the first and last "
                        "column; 0 = half the spacing (an even field)", 0.0),
        "MarginY": Prop("App::PropertyLength", "Layout",
                        "Distance from the field's edges (the walls) to the first and last row; "
                        "0 = half the spacing (an even field)", 0.0),
        "MountingOffset": Prop("App::PropertyLength", "Layout",
                               "Distance of the luminaires from the face: below a ceiling, "
                               "above a floor face", 50.0),
        "LuminaireRotation": Prop("App::PropertyAngle", "Layout",
                                  "Rotation of every luminaire about its aim (turns an area "
                                  "luminaire's Width/Length, a photometric file's C0)", 0.0),
        "ClipToWalls": Prop("App::PropertyBool", "Layout",
                            "Measure the field from the walls under the face (cut their "
                            "footprints out) rather than from the face's edges", True),
        "AreaLength": Prop("App::PropertyLength", "Rectangle",
                           "Without a face: the field's size along the Placement's X", 4000.0),
        "AreaWidth": Prop("App::PropertyLength", "Rectangle",
                          "Without a face: the field's size along the Placement's Y", 3000.0),
        "MemberCount": Prop("App::PropertyInteger", "Layout", "Luminaires placed", 0, READ_ONLY),
        **layout_type.PROPERTIES,
    }

    def __init__(self, obj: Any) -> None:
        super().__init__(obj)
        self.ready = True

    def onDocumentRestored(self, obj: Any) -> None:  # noqa: N802 (FreeCAD API name)
        """Older files gain the type properties, filled from the template."""
        super().onDocumentRestored(obj)
        self.ready = True
        layout_type.pull(obj)

    def onChanged(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        """Type properties edited on the layout go to its template (layout_type)."""
        layout_type.on_changed(obj, prop, getattr(self, "ready", False))

    def execute(self, obj: Any) -> None:
        """Markers for the members (the template's symbol at each) and MemberCount."""
        import Part

        layout_type.pull(obj)
        try:
            members = layout_placements(obj)
        except ValueError as exc:
            FreeCAD.Console.PrintWarning(f"{exc}\n")
            members = []
        if obj.MemberCount != len(members):
            obj.MemberCount = len(members)
        # Over a face the markers are global (Placement stays identity); a rectangle layout
        # keeps its Placement, so its markers are built relative to it.
        own = obj.Placement if _base_face_link(obj) is None else FreeCAD.Placement()
        local = own.inverse()
        shapes = [_marker(obj.Template, local.multiply(p)) for _, _, p in members]
        shape = Part.makeCompound(shapes) if shapes else Part.Shape()
        shape.Placement = own
        obj.Shape = shape
        if obj.Placement != own:
            obj.Placement = own


def _marker(template: Any, where: FreeCAD.Placement) -> Any:
    """The 3D marker of one member: the template's panel (area) or a disc, and its aim."""
    import Part

    kind = getattr(template, "LuminaireType", "Area")
    if kind == "Area":
        width, length = max(float(template.Width), 1.0), max(float(template.Length), 1.0)
        body = Part.makeBox(width, length, 20.0, V(-width / 2.0, -length / 2.0, 0.0))
    else:
        size = max(float(getattr(template, "SymbolSize", 150.0)), 1.0)
        body = Part.makeCylinder(size / 2.0, size / 3.0)
    aim = Part.makeLine(V(0, 0, 0), luminaire_mod.LOCAL_AIM * 300.0)
    marker = Part.makeCompound([body, aim])
    marker.Placement = where
    return marker


# -- geometry ----------------------------------------------------------------------------
def _base_face_link(obj: Any) -> Optional[Tuple[Any, str]]:
    link = obj.Base
    if not link or link[0] is None:
        return None
    subs = [s for s in (link[1] or []) if face_index(s) is not None]
    return link[0], (subs[0] if subs else "")


def field_frame(obj: Any) -> Tuple[placement.Frame, Optional[Any]]:
    """The field's frame (extent = the room region) and the region face (None: rectangle)."""
    found = _base_face_link(obj)
    if found is None:
        rot = obj.Placement.Rotation
        normal = rot.multVec(V(0, 0, -1))
        frame = placement.Frame(obj.Placement.Base, rot.multVec(V(1, 0, 0)),
                                rot.multVec(V(0, 1, 0)), normal, 0.0, float(obj.AreaLength),
                                0.0, float(obj.AreaWidth))
        return frame, None
    base, sub = found
    shape = global_shape(base)
    index = face_index(sub) if sub else (0 if len(shape.Faces) == 1 else None)
    if index is None:
        raise ValueError(f"Luminaire layout '{obj.Label}': select one face of '{base.Label}'")
    if index >= len(shape.Faces):
        raise ValueError(f"Luminaire layout '{obj.Label}': face {index + 1} of '{base.Label}' "
                         "no longer exists")
    face = shape.Faces[index]
    try:
        placement.face_frame(face)
    except ValueError:
        raise ValueError(f"Luminaire layout '{obj.Label}': the face of '{base.Label}' must be "
                         "planar") from None
    if obj.ClipToWalls:
        face = placement.room_region(face, placement.model_solids(obj.Document, (base.Name,)))
    frame = placement.face_frame(face)
    return frame, face


def axis_positions(count: int, start: float, end: float, spacing: float,
                   margin: float) -> List[float]:
    """Positions of ``count`` luminaires along a field from ``start`` to ``end``: spacing and
    margin both given: from start + margin every spacing; spacing only: centred; margin
    only: first and last at the margins, evenly between; neither: an even field
    (spacing = length / count, margins = half of it)."""
    length = end - start
    if count < 1:
        return []
    if spacing <= 0.0 and margin <= 0.0:
        spacing = length / count
        margin = spacing / 2.0
    elif spacing <= 0.0:
        spacing = (length - 2.0 * margin) / (count - 1) if count > 1 else 0.0
        if count == 1:
            margin = length / 2.0
    elif margin <= 0.0:
        margin = (length - (count - 1) * spacing) / 2.0
    return [start + margin + i * spacing for i in range(count)]


def member_rotation(aim: FreeCAD.Vector, x_axis: FreeCAD.Vector,
                    angle_deg: float) -> FreeCAD.Rotation:
    """The rotation taking local -Z to ``aim`` and local +X to ``x_axis`` turned by
    ``angle_deg`` about the aim's opposite (counter-clockwise seen from below a ceiling)."""
    z = aim * -1.0
    x = V(x_axis) - z * x_axis.dot(z)
    x.normalize()
    y = z.cross(x)
    base = FreeCAD.Rotation(x, y, z, "ZXY")
    return FreeCAD.Rotation(z, angle_deg).multiply(base)


def layout_placements(obj: Any) -> List[Tuple[str, str, FreeCAD.Placement]]:
    """(name, label, global placement) of every member, row by row; members whose point lies
    outside the field's face (e.g. an L-shaped room) are left out. ValueError names the
    object and property on bad input."""
    label = obj.Label
    rows, columns = int(obj.Rows), int(obj.Columns)
    if rows < 1 or columns < 1:
        raise ValueError(f"Luminaire layout '{label}': Rows and Columns must be >= 1 "
                         f"(got {rows} x {columns})")
    if rows * columns > MAX_MEMBERS:
        raise ValueError(f"Luminaire layout '{label}': {rows} x {columns} luminaires is more "
                         f"than {MAX_MEMBERS}")
    frame, face = field_frame(obj)
    us = axis_positions(columns, frame.u0, frame.u1, float(obj.SpacingX), float(obj.MarginX))
    vs = axis_positions(rows, frame.v0, frame.v1, float(obj.SpacingY), float(obj.MarginY))
    aim = placement.aim_for_normal(frame.normal) if face is not None else V(frame.normal)
    rotation = member_rotation(aim, frame.x, float(obj.LuminaireRotation))
    offset = frame.normal * float(obj.MountingOffset)
    out = []
    for r, v in enumerate(vs):
        for c, u in enumerate(us):
            point = frame.point(u, v)
            if face is not None and not face.isInside(point, 0.01, True):
                continue
            out.append((f"{obj.Name}_r{r + 1}c{c + 1}", f"{label} r{r + 1}c{c + 1}",
                        FreeCAD.Placement(point + offset, rotation)))
    return out


# -- members as luminaires ----------------------------------------------------------------
class LayoutMember:
    """One member, standing in for a luminaire object wherever the export and the checks
    read one (``scene_entry``, ``check``): the template's properties, its own Name, Label
    and Placement. ``layout`` is the document object to report problems against."""

    def __init__(self, layout: Any, name: str, label: str, where: FreeCAD.Placement) -> None:
        self.layout = layout
        self.template = layout.Template
        self.Name = name
        self.Label = label
        self.Placement = where

    def __getattr__(self, name: str) -> Any:
        # Only called for what the member does not have itself: the template's properties.
        return getattr(self.__dict__["template"], name)

    def getGlobalPlacement(self) -> FreeCAD.Placement:  # noqa: N802 (FreeCAD API name)
        return self.Placement


def members(obj: Any) -> List[LayoutMember]:
    """The layout's members ([] without a valid template)."""
    template = obj.Template
    if template is None or not _is_luminaire(template):
        return []
    return [LayoutMember(obj, n, lab, p) for n, lab, p in layout_placements(obj)]


def _is_luminaire(obj: Any) -> bool:
    from lighting.objects.base import proxy_type

    return proxy_type(obj) == luminaire_mod.TYPE


def layouts(analysis: Any) -> List[Any]:
    """The layouts an analysis uses (its group, plus those in no analysis)."""
    from lighting.objects import analysis as analysis_mod

    return analysis_mod.members(analysis, TYPE)


def template_names(doc: Any) -> set:
    """Names of the luminaires that are some layout's template (types, not placed)."""
    return {o.Template.Name for o in objects_of_type(doc, TYPE) if o.Template is not None}


def placed_luminaires(analysis: Any, report: Optional[Any] = None) -> List[Any]:
    """The luminaires an analysis puts in the room: its luminaire objects except layout
    templates, then every layout's members. A layout that cannot be laid out is reported
    (when ``report`` is given) and contributes none."""
    from lighting.objects import analysis as analysis_mod

    templates = template_names(analysis.Document)
    out = [o for o in analysis_mod.luminaires(analysis) if o.Name not in templates]
    for layout in layouts(analysis):
        try:
            out.extend(members(layout))
        except ValueError as exc:
            if report is not None:
                report.add("error", str(exc), layout.Name)
    return out


def report_name(lum: Any) -> str:
    """The document object a problem of ``lum`` is reported against (a member: its layout)."""
    return lum.layout.Name if isinstance(lum, LayoutMember) else lum.Name


# -- checks -------------------------------------------------------------------------------
def check(obj: Any) -> List[tuple]:
    """No template, bad counts, a field that the margins leave nothing of, lost members."""
    label = obj.Label
    template = obj.Template
    if template is None or not _is_luminaire(template):
        return [("error", f"Luminaire layout '{label}': Template must be a Lighting luminaire")]
    try:
        placed = layout_placements(obj)
        frame, _ = field_frame(obj)
    except ValueError as exc:
        return [("error", str(exc))]
    problems: List[tuple] = []
    wanted = int(obj.Rows) * int(obj.Columns)
    if not placed:
        problems.append(("error", f"Luminaire layout '{label}': no luminaire lies inside its "
                                  "field (margins or spacing too large?)"))
    elif len(placed) < wanted:
        problems.append(("warning", f"Luminaire layout '{label}': {wanted - len(placed)} of "
                                    f"{wanted} positions lie outside the face and are left out"))
    for axis, count, lo, hi, spacing, margin in (
            ("X", obj.Columns, frame.u0, frame.u1, obj.SpacingX, obj.MarginX),
            ("Y", obj.Rows, frame.v0, frame.v1, obj.SpacingY, obj.MarginY)):
        pos = axis_positions(int(count), lo, hi, float(spacing), float(margin))
        if pos and (pos[0] < lo - 1e-6 or pos[-1] > hi + 1e-6 or
                    (len(pos) > 1 and pos[1] <= pos[0])):
            problems.append(("error", f"Luminaire layout '{label}': Spacing{axis}/Margin{axis} "
                                      f"do not fit {int(count)} luminaires into the field's "
                                      f"{(hi - lo) / 1000.0:.2f} m"))
    return problems


def coincident_pairs(lums: Sequence[Any], tolerance_mm: float = 10.0) -> List[Tuple[Any, Any, float]]:
    """Pairs of luminaires whose positions are within ``tolerance_mm`` (and their distance):
    two light sources in one spot are a double click, not a design."""
    cell = max(tolerance_mm, 1e-6)
    buckets: Dict[Tuple[int, int, int], List[Tuple[Any, FreeCAD.Vector]]] = {}
    pairs = []
    for lum in lums:
        p = lum.getGlobalPlacement().Base
        key = tuple(int(math.floor(c / cell)) for c in (p.x, p.y, p.z))
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    near = (key[0] + dx, key[1] + dy, key[2] + dz)
                    for other, q in buckets.get(near, []):
                        distance = (p - q).Length
                        if distance <= tolerance_mm:
                            pairs.append((other, lum, distance))
        buckets.setdefault(key, []).append((lum, p))
    return pairs


# -- creation -----------------------------------------------------------------------------
def make_layout(doc: Any, template: Any, base: Any = None, face: Optional[str] = None,
                rows: int = 2, columns: int = 2, name: str = "LuminaireLayout",
                **lengths_mm: float) -> Any:
    """A layout document object; ``lengths_mm`` sets SpacingX/Y, MarginX/Y, MountingOffset,
    AreaLength/AreaWidth (mm) and LuminaireRotation (degrees) by property name."""
    obj = doc.addObject("Part::FeaturePython", name)
    LuminaireLayout(obj)
    obj.Template = template
    if base is not None:
        obj.Base = (base, [face] if face else [])
    obj.Rows, obj.Columns = int(rows), int(columns)
    for prop, value in lengths_mm.items():
        if prop not in LuminaireLayout.PROPERTIES:
            raise ValueError(f"Luminaire layout '{obj.Label}': no property {prop!r}")
        setattr(obj, prop, float(value))
    return obj
