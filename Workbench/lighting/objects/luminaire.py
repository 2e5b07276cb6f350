# SPDX-License-Identifier: LGPL-2.1-or-later
"""Luminaire: a light source placed by its Placement and aimed along its local -Z axis."""
from __future__ import annotations

import math
from typing import Any, Dict, List

import FreeCAD

from lighting.objects.base import BaseProxy, Prop, READ_ONLY
from lighting.units import vec_m

TYPE = "Lighting::Luminaire"
LUMINAIRE_TYPES = ("Point", "Spot", "Area")
#: The luminaire's aim in its own coordinates: the local -Z axis (like a downlight).
LOCAL_AIM = FreeCAD.Vector(0, 0, -1)


class Luminaire(BaseProxy):
    """Point (isotropic), spot (CIE beam/field angles) or area (one-sided Lambertian rectangle)
    luminaire. Position = ``Placement.Base``; aim = ``Placement.Rotation`` applied to -Z.

    The exported flux is the maintained flux: ``FluxLumen * MaintenanceFactor``, so the solver
    reports maintained illuminance Em (EN 12464-1)."""

    TYPE = TYPE
    VIEW_PROVIDER = ("luminaire", "ViewProviderLuminaire")
    PROPERTIES = {
        "LuminaireType": Prop("App::PropertyEnumeration", "Luminaire",
                              "Emission model: Point (isotropic), Spot (beam/field angles), "
                              "Area (Lambertian rectangle Width x Length facing the aim)",
                              "Area", items=LUMINAIRE_TYPES),
        "FluxLumen": Prop("App::PropertyFloat", "Luminaire",
                          "Initial luminous flux of the luminaire in lumens (lm)", 3000.0),
        "MaintenanceFactor": Prop("App::PropertyFloat", "Luminaire",
                                  "Maintenance factor MF = LLMF*LSF*LMF*RSMF (0..1]; the solver "
                                  "gets FluxLumen*MF, so results are maintained values", 0.8),
        "BeamAngle": Prop("App::PropertyAngle", "Spot",
                          "Spot: full angle where the intensity falls to 50 % of the peak", 40.0),
        "FieldAngle": Prop("App::PropertyAngle", "Spot",
                           "Spot: full angle where the intensity falls to 10 % of the peak", 70.0),
        "Width": Prop("App::PropertyLength", "Area",
                      "Area: luminous width along the local X axis", 600.0),
        "Length": Prop("App::PropertyLength", "Area",
                       "Area: luminous length along the local Y axis", 600.0),
        "SymbolSize": Prop("App::PropertyLength", "Display",
                           "Size of the 3D symbol of point and spot luminaires", 150.0),
        "AimDirection": Prop("App::PropertyVector", "Luminaire",
                             "Aim (unit vector, global), from the Placement's rotation",
                             FreeCAD.Vector(0, 0, -1), READ_ONLY),
    }

    def execute(self, obj: Any) -> None:
        """Build the symbol: sphere (point), cone (spot) or thin panel (area), plus an aim line."""
        import Part

        size = max(float(obj.SymbolSize), 1.0)
        kind = obj.LuminaireType
        shapes: List[Any] = []
        if kind == "Point":
            shapes.append(Part.makeSphere(size / 2.0))
        elif kind == "Spot":
            half = math.radians(min(max(float(obj.BeamAngle), 1.0), 170.0) / 2.0)
            radius = min(size * math.tan(half), 2.0 * size)
            shapes.append(Part.makeCone(radius, 0.0, size, FreeCAD.Vector(0, 0, -size),
                                        FreeCAD.Vector(0, 0, 1)))
        else:
            width = max(float(obj.Width), 1.0)
            length = max(float(obj.Length), 1.0)
            # The emitting face is the panel's bottom at local z = 0; the body sits above it.
            shapes.append(Part.makeBox(width, length, 20.0,
                                       FreeCAD.Vector(-width / 2.0, -length / 2.0, 0.0)))
        if kind != "Point":
            shapes.append(Part.makeLine(FreeCAD.Vector(0, 0, 0), LOCAL_AIM * (2.0 * size)))
        shape = Part.makeCompound(shapes)
        shape.Placement = obj.Placement
        obj.Shape = shape
        aim = aim_direction(obj)
        if (obj.AimDirection - aim).Length > 1e-12:
            obj.AimDirection = aim

    def onChanged(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        """Keep AimDirection in step with the placement without a recompute."""
        if prop == "Placement" and "AimDirection" in obj.PropertiesList:
            aim = aim_direction(obj)
            if (obj.AimDirection - aim).Length > 1e-12:
                obj.AimDirection = aim


def aim_direction(obj: Any) -> FreeCAD.Vector:
    """Unit aim vector of a luminaire in global coordinates."""
    placement = obj.getGlobalPlacement() if hasattr(obj, "getGlobalPlacement") else obj.Placement
    aim = placement.Rotation.multVec(LOCAL_AIM)
    return aim.normalize() if aim.Length > 0 else FreeCAD.Vector(0, 0, -1)


def rotation_for_aim(aim: FreeCAD.Vector) -> FreeCAD.Rotation:
    """The rotation that turns the local -Z axis onto ``aim`` (keeps X level where possible)."""
    target = FreeCAD.Vector(aim)
    if target.Length == 0:
        raise ValueError("aim direction must not be the zero vector")
    target.normalize()
    return FreeCAD.Rotation(LOCAL_AIM, target)


def maintained_flux_lm(obj: Any) -> float:
    """Flux handed to the solver: initial flux times the maintenance factor."""
    return float(obj.FluxLumen) * float(obj.MaintenanceFactor)


def scene_entry(obj: Any) -> Dict[str, Any]:
    """The luminaire as a ``luminaires[]`` entry of docs/scene-format.md (metres, lumens)."""
    placement = obj.getGlobalPlacement()
    position = placement.Base
    aim = aim_direction(obj)
    entry: Dict[str, Any] = {"name": obj.Name, "type": obj.LuminaireType.lower(),
                             "flux_lm": maintained_flux_lm(obj)}
    kind = obj.LuminaireType
    if kind == "Point":
        entry["position"] = vec_m(position)
    elif kind == "Spot":
        entry["position"] = vec_m(position)
        entry["direction"] = [aim.x, aim.y, aim.z]
        entry["beam_angle_deg"] = float(obj.BeamAngle)
        entry["field_angle_deg"] = float(obj.FieldAngle)
    else:
        rot = placement.Rotation
        # edge1 x edge2 must point along the aim (-Z local): Y x X = -Z.
        edge1 = rot.multVec(FreeCAD.Vector(0, float(obj.Length), 0))
        edge2 = rot.multVec(FreeCAD.Vector(float(obj.Width), 0, 0))
        corner = position - edge1 * 0.5 - edge2 * 0.5
        entry["corner"] = vec_m(corner)
        entry["edge1"] = vec_m(edge1)
        entry["edge2"] = vec_m(edge2)
    return entry


def check(obj: Any) -> List[tuple]:
    """Absurd or invalid values: list of (level, text)."""
    problems: List[tuple] = []
    name = obj.Label
    flux = float(obj.FluxLumen)
    mf = float(obj.MaintenanceFactor)
    if not math.isfinite(flux) or flux <= 0.0:
        problems.append(("error", f"Luminaire '{name}': flux must be > 0 lm (got {flux:g})"))
    elif flux > 1.0e6:
        problems.append(("warning", f"Luminaire '{name}': flux {flux:g} lm is implausibly high "
                                    "for one luminaire (> 1 000 000 lm)"))
    if not (0.0 < mf <= 1.0):
        problems.append(("error", f"Luminaire '{name}': maintenance factor must be in (0, 1] "
                                  f"(got {mf:g})"))
    elif mf < 0.3:
        problems.append(("warning", f"Luminaire '{name}': maintenance factor {mf:g} is unusually low"))
    if obj.LuminaireType == "Spot":
        beam, field = float(obj.BeamAngle), float(obj.FieldAngle)
        if not (0.0 < beam < field <= 360.0):
            problems.append(("error", f"Luminaire '{name}': spot angles need 0 < beam < field <= "
                                      f"360 deg (got beam {beam:g}, field {field:g})"))
    if obj.LuminaireType == "Area" and (float(obj.Width) <= 0.0 or float(obj.Length) <= 0.0):
        problems.append(("error", f"Luminaire '{name}': area luminaire needs Width and Length > 0"))
    return problems
