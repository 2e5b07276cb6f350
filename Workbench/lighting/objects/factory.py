# SPDX-License-Identifier: LGPL-2.1-or-later
"""make_* functions creating the Lighting objects (like FEM's ObjectsFem.py).

They are App code and work headless; in the GUI, lighting/viewproviders/observer.py gives
the new objects their view providers. Lengths in the Python API are metres (``height_m``),
flux in lumens (``flux_lm``)."""
from __future__ import annotations

from typing import Any, Dict, Iterable, Optional, Sequence, Tuple, Union

import FreeCAD

from lighting.units import M_TO_MM

Vec = Union[FreeCAD.Vector, Sequence[float]]


def _vec_mm(point_m: Vec) -> FreeCAD.Vector:
    if isinstance(point_m, FreeCAD.Vector):
        return point_m * M_TO_MM
    x, y, z = point_m
    return FreeCAD.Vector(x, y, z) * M_TO_MM


def _add_to_analysis(obj: Any, analysis: Optional[Any]) -> None:
    if analysis is not None:
        analysis.addObject(obj)


def make_analysis(doc: Any, name: str = "LightingAnalysis", photons: Optional[int] = None,
                  seed: Optional[int] = None) -> Any:
    """Create a Lighting analysis (solver settings and results) in ``doc``."""
    from lighting.objects.analysis import Analysis

    obj = doc.addObject("App::DocumentObjectGroupPython", name)
    Analysis(obj)
    if photons is not None:
        obj.Photons = int(photons)
    if seed is not None:
        obj.Seed = int(seed)
    return obj


def make_luminaire(doc: Any, position_m: Vec = (0.0, 0.0, 2.5), kind: str = "Area",
                   flux_lm: float = 3000.0, maintenance_factor: float = 0.8,
                   aim: Vec = (0.0, 0.0, -1.0), width_m: float = 0.6, length_m: float = 0.6,
                   beam_angle_deg: float = 40.0, field_angle_deg: float = 70.0,
                   name: str = "Luminaire", analysis: Optional[Any] = None) -> Any:
    """Create a luminaire at ``position_m`` aimed along ``aim`` (default straight down).

    ``kind`` is "Point", "Spot" or "Area"; ``flux_lm`` the initial flux, the exported flux is
    ``flux_lm * maintenance_factor``."""
    from lighting.objects.luminaire import LUMINAIRE_TYPES, Luminaire, rotation_for_aim

    kind = kind.capitalize()
    if kind not in LUMINAIRE_TYPES:
        raise ValueError(f"luminaire kind must be one of {LUMINAIRE_TYPES} (got {kind!r})")
    obj = doc.addObject("Part::FeaturePython", name)
    Luminaire(obj)
    obj.LuminaireType = kind
    obj.FluxLumen = float(flux_lm)
    obj.MaintenanceFactor = float(maintenance_factor)
    obj.Width = width_m * M_TO_MM
    obj.Length = length_m * M_TO_MM
    obj.BeamAngle = beam_angle_deg
    obj.FieldAngle = field_angle_deg
    aim_vec = FreeCAD.Vector(*aim) if not isinstance(aim, FreeCAD.Vector) else aim
    obj.Placement = FreeCAD.Placement(_vec_mm(position_m), rotation_for_aim(aim_vec))
    _add_to_analysis(obj, analysis)
    return obj


def face_target_label(links: Sequence[Tuple[Any, Sequence[str]]]) -> str:
    """A label that says what a face target covers: "Target Wall001 Face3",
    "Target Desk Face6, Face7", "Target Wall Face3 +4 faces"."""
    if not links:
        return "Target"
    first, subs = links[0]
    shown = list(subs[:2])
    rest = sum(len(s) for _, s in links) - len(shown)
    text = f"Target {first.Label} {', '.join(shown)}".rstrip()
    return f"{text} +{rest} face{'s' if rest > 1 else ''}" if rest > 0 else text


def make_face_target(doc: Any, faces: Iterable[Tuple[Any, Union[str, Sequence[str]]]],
                     name: Optional[str] = None, required_lux: float = 0.0,
                     analysis: Optional[Any] = None) -> Any:
    """Create a target over faces: ``faces`` is [(object, "Face3"), (object, ["Face1", ...])].
    The target reports illuminance on the faces' outward side. Without ``name`` it is called
    "Target" and labelled after its faces ("Target Wall001 Face3")."""
    from lighting.objects.target import Target

    links = []
    for obj, subs in faces:
        links.append((obj, (subs,) if isinstance(subs, str) else tuple(subs)))
    obj = doc.addObject("Part::FeaturePython", name or "Target")
    if name is None:
        obj.Label = face_target_label(links)
    Target(obj)
    obj.TargetType = "Faces"
    obj.References = links
    obj.RequiredLux = float(required_lux)
    _add_to_analysis(obj, analysis)
    return obj


def _refuse_curved_face(base: Any, face: str) -> None:
    """ValueError, before anything is made, for a grid on a curved face (a cylinder's side):
    a grid is a plane; its bounding box would be accepted and then leave "no area"."""
    from lighting.geometry import face_index, global_shape, is_planar

    index = face_index(face)
    faces = global_shape(base).Faces if hasattr(base, "Shape") else []
    if index is None or index >= len(faces):
        raise ValueError(f"calculation grid: '{base.Label}' has no face {face!r}")
    if not is_planar(faces[index]):
        raise ValueError(f"calculation grid: '{base.Label}.{face}' is curved; a grid lies on a "
                         "plane: select a flat face (a floor, a wall's inner face, a ceiling's "
                         "underside) or the floor, slab or Arch space itself")


def make_grid_target(doc: Any, base: Any, face: Optional[str] = None, height_m: float = 0.80,
                     wall_band_m: Optional[float] = None, spacing_m: float = 0.0,
                     required_lux: float = 0.0, required_uniformity: float = 0.0,
                     name: str = "Workplane", analysis: Optional[Any] = None,
                     surface: str = "Work plane", offset_m: Optional[float] = None,
                     activity: Optional[str] = None) -> Any:
    """Create a calculation grid. ``surface`` "Work plane" (default): over a floor/slab/space
    ``base`` (or one of its faces) at ``height_m``; "Wall", "Ceiling", "Floor": on the planar
    ``face`` of ``base``, ``offset_m`` in front of it (default 0.01 m), facing the room.
    ``wall_band_m`` is the border band left out (default: 0.5 m for work planes and floors, 0
    for walls and ceilings); ``spacing_m`` 0 = EN 12464-1 rule; ``activity`` (one of
    ``lighting.standards.ACTIVITIES``) presets the requirements and overrides ``required_*``."""
    from lighting import standards
    from lighting.objects.target import Target

    if surface not in standards.SURFACE_KINDS:
        raise ValueError(f"surface must be one of {standards.SURFACE_KINDS} (got {surface!r})")
    if activity is not None and activity not in standards.ACTIVITIES:
        raise ValueError(f"activity must be one of {standards.ACTIVITIES} (got {activity!r})")
    if face:
        _refuse_curved_face(base, face)
    band = standards.BORDER_BAND_M[surface] if wall_band_m is None else wall_band_m
    obj = doc.addObject("Part::FeaturePython", name)
    Target(obj)
    obj.TargetType = "Grid"
    obj.Base = (base, [face] if face else [])
    obj.WorkplaneHeight = height_m * M_TO_MM
    obj.WallBand = band * M_TO_MM
    obj.Spacing = spacing_m * M_TO_MM
    obj.RequiredLux = float(required_lux)
    obj.RequiredUniformity = float(required_uniformity)
    obj.Surface = surface
    if offset_m is not None:
        obj.Offset = offset_m * M_TO_MM
    if activity is not None:
        obj.Activity = activity
    _add_to_analysis(obj, analysis)
    return obj


def make_observer(doc: Any, position_m: Vec = (0.0, 0.0, 1.2), view: Vec = (1.0, 0.0, 0.0),
                  ugr_max: Optional[float] = None, posture: str = "Seated",
                  name: str = "Observer", analysis: Optional[Any] = None) -> Any:
    """Create an observer (an eye for UGR) at ``position_m`` looking along ``view`` (level:
    its z is dropped), with the UGR limit ``ugr_max`` (0: none); None: the limit of the
    analysis' activity (the strictest EN 12464-1 preset of its targets, observer.activity_of),
    else none."""
    from lighting.objects.analysis import find_analysis
    from lighting.objects.observer import LOCAL_VIEW, Observer, activity_of

    level = FreeCAD.Vector(view[0], view[1], 0.0)
    if level.Length == 0.0:
        raise ValueError(f"observer {name!r}: the view direction must not be vertical or zero")
    obj = doc.addObject("Part::FeaturePython", name)
    Observer(obj)
    obj.Placement = FreeCAD.Placement(
        FreeCAD.Vector(*(c * M_TO_MM for c in position_m)),
        FreeCAD.Rotation(LOCAL_VIEW, level.normalize()))
    if ugr_max is None:
        obj.Activity = activity_of(analysis or find_analysis(doc))  # fills UgrMax
    else:
        obj.UgrMax = float(ugr_max)
    obj.Posture = posture
    _add_to_analysis(obj, analysis)
    return obj


def make_light_scene(analysis: Any, name: str = "Light scene",
                     levels: Optional[Dict[str, float]] = None) -> Any:
    """Create a light scene in ``analysis``: every control group of its luminaires at level 1
    (full flux), then ``levels`` ({group: level}, 0 = off). It turns the analysis'
    Contributions on (the next run traces each group separately) and is shown from then on;
    switching scenes or changing levels rescales that run, no tracing
    (objects/light_scene.py)."""
    from lighting.objects import light_scene

    return light_scene.make(analysis, name, levels)


def show_light_scene(analysis: Any, scene: Optional[Any] = None) -> None:
    """Show ``scene`` (a light scene of the analysis, or its Label) in the analysis' results,
    or the results as traced when None."""
    from lighting.objects import light_scene

    if isinstance(scene, str):
        found = [s for s in light_scene.scenes(analysis) if scene in (s.Name, s.Label)]
        if not found:
            raise ValueError(f"analysis '{analysis.Label}' has no light scene {scene!r}")
        scene = found[0]
    if scene is not None and light_scene.analysis_of(scene) is not analysis:
        raise ValueError(f"light scene '{scene.Label}' is not in analysis '{analysis.Label}'")
    if analysis.ActiveLightScene is not scene:
        analysis.ActiveLightScene = scene


def make_placement_domain(doc: Any, base: Any, face: str, resolution_m: float = 0.6,
                          max_luminaires: int = 4, offset_m: float = 0.05,
                          edge_margin_m: float = 0.3, template: Optional[Any] = None,
                          name: str = "PlacementDomain", analysis: Optional[Any] = None) -> Any:
    """Create a placement domain on ``base.face`` (e.g. the ceiling's underside)."""
    from lighting.objects.placement_domain import PlacementDomain

    obj = doc.addObject("Part::FeaturePython", name)
    PlacementDomain(obj)
    obj.Base = (base, [face])
    obj.Resolution = resolution_m * M_TO_MM
    obj.MaxLuminaires = int(max_luminaires)
    obj.MountingOffset = offset_m * M_TO_MM
    obj.EdgeMargin = edge_margin_m * M_TO_MM
    obj.Template = template
    _add_to_analysis(obj, analysis)
    return obj


def make_sky(doc: Any, model: str = "CIE overcast", diffuse_horizontal_lx: float = 10000.0,
             windows: Optional[Sequence[Any]] = None, name: str = "Sky",
             analysis: Optional[Any] = None) -> Any:
    """Create a Sky (objects/sky.py): ``model`` one of its SkyModel choices, at
    ``diffuse_horizontal_lx``; its portals are the openings of ``windows`` (default: every
    Arch window hosted in a wall, found at each recompute)."""
    from lighting.objects.sky import MODELS, Sky

    if model not in MODELS:
        raise ValueError(f"model must be one of {tuple(MODELS)} (got {model!r})")
    obj = doc.addObject("Part::FeaturePython", name)
    Sky(obj)
    obj.SkyModel = model
    obj.DiffuseHorizontalLux = float(diffuse_horizontal_lx)
    if windows:
        obj.Windows = list(windows)
    _add_to_analysis(obj, analysis)
    return obj
