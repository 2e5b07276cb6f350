# SPDX-License-Identifier: LGPL-2.1-or-later
"""Build a small office with Arch walls, a window, a desk, a cabinet mesh and four ceiling
luminaires, plus the Lighting targets and analysis — the model of Examples/office.py and of
the workbench tests.

Room: 5.0 x 4.0 m inside, 3.0 m high; 0.2 m walls, floor and ceiling slabs; a 1.5 x 1.2 m
window in the south wall (y = 0); a desk (Part fusion with a ``Reflectance`` property); a
cabinet (Mesh::Feature); four 0.6 x 0.6 m area luminaires 5 cm under the ceiling.

Usage in any FreeCAD Python (headless or GUI)::

    import office_model
    doc = office_model.build_office()            # new document "Office"
    objects = office_model.OBJECTS               # names of the interesting objects
"""
from __future__ import annotations

from typing import Any, Dict, Optional

import FreeCAD
import Mesh

import lighting
from lighting.compat import import_arch

V = FreeCAD.Vector
ROOM_X_MM, ROOM_Y_MM, ROOM_Z_MM = 5000.0, 4000.0, 3000.0
WALL_MM = 200.0
SLAB_MM = 200.0
LUMINAIRE_FLUX_LM = 5200.0
MAINTENANCE_FACTOR = 0.8

#: Object names by role, filled by build_office().
OBJECTS: Dict[str, str] = {}


def find_face(shape: Any, normal: FreeCAD.Vector, point: FreeCAD.Vector,
              tolerance_mm: float = 1.0) -> str:
    """Name ("FaceN") of the planar face of ``shape`` with the given outward normal whose
    plane passes through ``point``; the largest one if several do."""
    best, best_area = None, -1.0
    for index, face in enumerate(shape.Faces):
        if face.Surface.TypeId != "Part::GeomPlane":
            continue
        u0, u1, v0, v1 = face.ParameterRange
        n = face.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1))
        if n.getAngle(normal) > 1e-3:
            continue
        if abs((point - face.Vertexes[0].Point).dot(n)) > tolerance_mm:
            continue
        if face.Area > best_area:
            best, best_area = f"Face{index + 1}", face.Area
    if best is None:
        raise ValueError(f"no face with normal {normal} through {point}")
    return best


def prepare_gui_view(doc: Any) -> None:
    """Give ``doc`` an active 3D view when the GUI is up, before any Arch object recomputes.

    With the GUI up, Arch's profile-based objects (structures, walls) ask Draft's
    ``get_normal`` for the active 3D view to orient their profile (it flips a normal that
    points away from the viewer) and fail with "'NoneType' object has no attribute
    'getViewDirection'" when the GUI has no active document with a 3D view, as right after
    FreeCAD starts on its Start page. An isometric view never looks along a slab's normal,
    so the profiles keep the orientation they have headless. Headless this does nothing."""
    if not FreeCAD.GuiUp:
        return
    import FreeCADGui

    gui_doc = FreeCADGui.getDocument(doc.Name)
    FreeCADGui.setActiveDocument(doc.Name)
    if not gui_doc.mdiViewsOfType("Gui::View3DInventor"):
        FreeCADGui.activateView("Gui::View3DInventor", True)
    views = gui_doc.mdiViewsOfType("Gui::View3DInventor")
    if FreeCADGui.ActiveDocument is None or not views:
        raise RuntimeError(f"office_model: document {doc.Name!r} has no 3D view (a hidden "
                           "document?); Arch objects cannot be built in it while the GUI is up")
    views[0].viewIsometric()


def _slab(arch: Any, doc: Any, name: str, z_mm: float) -> Any:
    slab = arch.makeStructure(None, length=ROOM_X_MM + 2 * WALL_MM,
                              width=ROOM_Y_MM + 2 * WALL_MM, height=SLAB_MM)
    slab.Label = name
    slab.IfcType = "Slab"
    # makeStructure centres the profile on the placement.
    slab.Placement.Base = V(ROOM_X_MM / 2, ROOM_Y_MM / 2, z_mm)
    return slab


def build_office(doc: Optional[Any] = None, photons: int = 200000, seed: int = 1) -> Any:
    """Create the office in ``doc`` (default: a new document "Office"); returns the document."""
    import Draft

    arch = import_arch()
    doc = doc or FreeCAD.newDocument("Office")
    prepare_gui_view(doc)
    # Walls around the room: a closed outline without a face (else Arch fills it), the
    # walls on its outer side ("Left" for this counter-clockwise outline), so the room keeps
    # its inner size.
    outline = Draft.makeWire([V(0, 0, 0), V(ROOM_X_MM, 0, 0), V(ROOM_X_MM, ROOM_Y_MM, 0),
                              V(0, ROOM_Y_MM, 0)], closed=True)
    outline.MakeFace = False
    outline.Label = "WallOutline"
    walls = arch.makeWall(outline, width=WALL_MM, height=ROOM_Z_MM, align="Left")
    walls.Label = "Walls"
    floor = _slab(arch, doc, "Floor", -SLAB_MM)
    ceiling = _slab(arch, doc, "Ceiling", ROOM_Z_MM)
    doc.recompute()

    # A fixed window in the south wall (y = 0 .. -0.2 m): frame 100 mm deep, glass 10 mm.
    window = arch.makeWindowPreset("Fixed", width=1500.0, height=1200.0, h1=50.0, h2=50.0,
                                   h3=50.0, w1=100.0, w2=10.0, o1=0.0, o2=45.0)
    window.Label = "Window"
    window.Placement = FreeCAD.Placement(V(1750.0, -50.0, 900.0), FreeCAD.Rotation(V(1, 0, 0), 90))
    window.Hosts = [walls]
    doc.recompute()

    # Desk: a top and two side panels fused; its material comes from a Reflectance property.
    parts = []
    for name, size, pos in (("DeskTop", (1600, 800, 25), (1700, 2400, 725)),
                            ("DeskSideL", (25, 800, 725), (1700, 2400, 0)),
                            ("DeskSideR", (25, 800, 725), (3275, 2400, 0))):
        box = doc.addObject("Part::Box", name)
        box.Length, box.Width, box.Height = size
        box.Placement.Base = V(*pos)
        parts.append(box)
    desk = doc.addObject("Part::MultiFuse", "Desk")
    desk.Shapes = parts
    desk.Refine = True
    desk.addProperty("App::PropertyFloat", "Reflectance", "Lighting", "Diffuse reflectance (0..1)")
    desk.Reflectance = 0.45
    # Cabinet: a furniture mesh (closed box), default furniture material.
    cabinet = doc.addObject("Mesh::Feature", "Cabinet")
    cabinet.Mesh = Mesh.createBox(800.0, 400.0, 1200.0)
    cabinet.Placement.Base = V(4500.0, 3750.0, 600.0)
    # The room volume as an Arch space: the calculation grid's base.
    volume = doc.addObject("Part::Box", "RoomVolume")
    volume.Length, volume.Width, volume.Height = ROOM_X_MM, ROOM_Y_MM, ROOM_Z_MM
    space = arch.makeSpace(volume)
    space.Label = "Office"
    # The space is not geometry (never exported); hidden, it does not hide the room in the GUI.
    space.Visibility = False
    volume.Visibility = False
    doc.recompute()

    analysis = lighting.make_analysis(doc, photons=photons, seed=seed)
    for i, (x, y) in enumerate(((1250, 1000), (3750, 1000), (1250, 3000), (3750, 3000))):
        lighting.make_luminaire(doc, (x / 1000.0, y / 1000.0, (ROOM_Z_MM - 50.0) / 1000.0),
                                kind="Area", flux_lm=LUMINAIRE_FLUX_LM,
                                maintenance_factor=MAINTENANCE_FACTOR, name=f"Luminaire{i + 1:02d}",
                                analysis=analysis)
    workplane = lighting.make_grid_target(doc, space, height_m=0.80, wall_band_m=0.50,
                                          required_lux=500.0, required_uniformity=0.60,
                                          name="Workplane", analysis=analysis)
    doc.recompute()
    desk_face = find_face(desk.Shape, V(0, 0, 1), V(0, 0, 750))
    desk_target = lighting.make_face_target(doc, [(desk, desk_face)], name="DeskTop_target",
                                            required_lux=500.0, analysis=analysis)
    desk_target.Label = "Desk top"
    wall_face = find_face(walls.Shape, V(0, -1, 0), V(0, ROOM_Y_MM, 0))
    wall_target = lighting.make_face_target(doc, [(walls, wall_face)], name="NorthWall",
                                            required_lux=150.0, analysis=analysis)
    wall_target.Label = "North wall"
    ceiling_face = find_face(ceiling.Shape, V(0, 0, -1), V(0, 0, ROOM_Z_MM))
    lighting.make_placement_domain(doc, ceiling, ceiling_face, resolution_m=0.6,
                                   max_luminaires=6, template=doc.getObject("Luminaire01"),
                                   name="CeilingDomain", analysis=analysis)
    doc.recompute()
    OBJECTS.update({"walls": walls.Name, "floor": floor.Name, "ceiling": ceiling.Name,
                    "window": window.Name, "desk": desk.Name, "cabinet": cabinet.Name,
                    "space": space.Name, "analysis": analysis.Name, "workplane": workplane.Name,
                    "desk_target": desk_target.Name, "wall_target": wall_target.Name,
                    "desk_face": desk_face, "wall_face": wall_face})
    return doc


def show_in_gui(doc: Any, ceiling_transparency: int = 80) -> None:
    """Present the office in the GUI (nothing headless): the Lighting workbench active, the
    ceiling transparent so the false colours below it show (it stays visible and in the
    lighting model: hiding is a viewing choice, transparency keeps it on screen), the
    document's 3D view active, isometric and fitted."""
    if not FreeCAD.GuiUp:
        return
    import FreeCADGui

    FreeCADGui.activateWorkbench("LightingWorkbench")
    FreeCADGui.Selection.clearSelection()  # Arch leaves the wall outline selected
    ceiling = doc.getObject(OBJECTS.get("ceiling", "")) if OBJECTS.get("ceiling") else None
    if ceiling is not None:
        ceiling.ViewObject.Visibility = True
        ceiling.ViewObject.Transparency = ceiling_transparency
    FreeCADGui.setActiveDocument(doc.Name)
    views = FreeCADGui.getDocument(doc.Name).mdiViewsOfType("Gui::View3DInventor")
    if views:
        FreeCADGui.activateView("Gui::View3DInventor", False)
        views[0].viewIsometric()
        views[0].fitAll()
