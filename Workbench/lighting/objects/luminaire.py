# SPDX-License-Identifier: LGPL-2.1-or-later
"""Luminaire: a light source placed by its Placement and aimed along its local -Z axis."""
from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional

import FreeCAD

from lighting.objects.base import BaseProxy, Prop, READ_ONLY
from lighting.units import vec_m

TYPE = "Lighting::Luminaire"
#: The luminaire's aim in its own coordinates: the local -Z axis (like a downlight).
LOCAL_AIM = FreeCAD.Vector(0, 0, -1)


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


def maintained_flux_lm(obj: Any) -> Optional[float]:
    """Flux handed to the solver: initial flux times the maintenance factor. Photometric
    luminaires with FluxLumen = 0 use the file's rated lumens; None when the file has
    absolute photometry (the solver then emits the file's own flux). Other values, 0 (switched
    off) and invalid ones alike, go to the solver as they are: its check is the one rule."""
    flux = float(obj.FluxLumen)
    if obj.LuminaireType == "Photometric" and flux == 0.0:
        from lighting.photometry import rated_lumens

        rated = rated_lumens(str(obj.PhotometricFile))
        if rated is None:
            return None
        flux = rated
    return flux * float(obj.MaintenanceFactor)


def c0_rotation_deg(aim: FreeCAD.Vector, c0: FreeCAD.Vector) -> float:
    """The scene's ``rotation_deg`` turning the solver's default C0 (+x, or +y when aiming
    along x) counter-clockwise about the luminaire's up axis (-aim) onto ``c0``
    (docs/scene-format.md: c0 = cos(a) ref + sin(a) ref x aim)."""
    ref = FreeCAD.Vector(0, 1, 0) if abs(aim.x) > 0.999 else FreeCAD.Vector(1, 0, 0)
    ref = (ref - aim * ref.dot(aim)).normalize()
    return math.degrees(math.atan2(ref.cross(aim).dot(c0), ref.dot(c0)))


def scene_entry(obj: Any) -> Dict[str, Any]:
    """The luminaire as a ``luminaires[]`` entry of docs/scene-format.md (metres, lumens).
    Photometric entries name the file by its absolute path; the scene writer copies it."""
    kind = kind_of(obj)
    entry: Dict[str, Any] = {"name": obj.Name, "type": kind.scene_type}
    flux = maintained_flux_lm(obj)
    if flux is not None:
        entry["flux_lm"] = flux
    entry.update(kind.keys(obj, obj.getGlobalPlacement(), aim_direction(obj)))
    entry["group"] = control_group(obj)
    return entry


def control_group(obj: Any) -> str:
    """The luminaire's control group: its ControlGroup; empty, a layout member's is the
    layout's Name (the layout is switched and dimmed as one) and a luminaire's its own Name."""
    named = str(getattr(obj, "ControlGroup", "") or "").strip()
    if named:
        return named
    layout = getattr(obj, "layout", None)
    return str(layout.Name) if layout is not None else str(obj.Name)


def check(obj: Any) -> List[tuple]:
    """Checks of what only the document has: list of (level, text). Values the scene file
    carries (flux, spot angles, the photometric file's content) are checked by the solver's
    validator in the Check stage (solver/check.py); 0 lm is a switched-off luminaire
    (docs/scene-format.md)."""
    problems: List[tuple] = []
    name = obj.Label
    flux = float(obj.FluxLumen)
    mf = float(obj.MaintenanceFactor)
    if math.isfinite(flux) and flux > 1.0e6:
        problems.append(("warning", f"Luminaire '{name}': flux {flux:g} lm is implausibly high "
                                    "for one luminaire (> 1 000 000 lm)"))
    # The maintenance factor never reaches the scene (it scales the flux): checked here.
    if not (0.0 < mf <= 1.0):
        problems.append(("error", f"Luminaire '{name}': maintenance factor must be in (0, 1] "
                                  f"(got {mf:g})"))
    elif mf < 0.3:
        problems.append(("warning", f"Luminaire '{name}': maintenance factor {mf:g} is unusually low"))
    problems.extend(kind_of(obj).check(obj))
    return problems


def _check_area(obj: Any) -> List[tuple]:
    """Width and Length become edge vectors: a negative one would silently turn the emitter
    over."""
    if float(obj.Width) <= 0.0 or float(obj.Length) <= 0.0:
        return [("error", f"Luminaire '{obj.Label}': area luminaire needs Width and Length > 0")]
    return []


def _check_photometric(obj: Any) -> List[tuple]:
    """The file property, and the maintenance factor a file's own absolute flux cannot take;
    the file's content is the solver's to check (lighting.photometry reads it natively)."""
    from lighting.photometry import rated_lumens

    name, path = obj.Label, str(obj.PhotometricFile)
    if not path or not os.path.isfile(path):
        return [("error", f"Luminaire '{name}': photometric file '{path}' not found")]
    if float(obj.FluxLumen) != 0.0 or float(obj.MaintenanceFactor) == 1.0:
        return []
    try:
        rated = rated_lumens(path)
    except (OSError, ValueError) as exc:
        return [("error", f"Luminaire '{name}': {exc}")]
    if rated is None:
        return [("warning", f"Luminaire '{name}': the file has absolute photometry and FluxLumen "
                            "is 0, so the maintenance factor is not applied; set FluxLumen")]
    return []


# -- the luminaire types: one row each ---------------------------------------------------------
def _sphere(obj: Any, size: float) -> List[Any]:
    import Part

    return [Part.makeSphere(size / 2.0)]


def _cone(obj: Any, size: float) -> List[Any]:
    import Part

    half = math.radians(min(max(float(obj.BeamAngle), 1.0), 170.0) / 2.0)
    radius = min(size * math.tan(half), 2.0 * size)
    return [Part.makeCone(radius, 0.0, size, FreeCAD.Vector(0, 0, -size), FreeCAD.Vector(0, 0, 1))]


def _panel(obj: Any, size: float) -> List[Any]:
    import Part

    width, length = max(float(obj.Width), 1.0), max(float(obj.Length), 1.0)
    # The emitting face is the panel's bottom at local z = 0; the body sits above it.
    return [Part.makeBox(width, length, 20.0, FreeCAD.Vector(-width / 2.0, -length / 2.0, 0.0))]


def _drum(obj: Any, size: float) -> List[Any]:
    import Part

    # A drum with a line along local +X: the photometric C0 plane.
    return [Part.makeCylinder(size / 2.0, size / 3.0),
            Part.makeLine(FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(size, 0, 0))]


def _point_keys(obj: Any, placement: Any, aim: FreeCAD.Vector) -> Dict[str, Any]:
    return {"position": vec_m(placement.Base)}


def _spot_keys(obj: Any, placement: Any, aim: FreeCAD.Vector) -> Dict[str, Any]:
    return {"position": vec_m(placement.Base), "direction": [aim.x, aim.y, aim.z],
            "beam_angle_deg": float(obj.BeamAngle), "field_angle_deg": float(obj.FieldAngle)}


def _area_keys(obj: Any, placement: Any, aim: FreeCAD.Vector) -> Dict[str, Any]:
    rot = placement.Rotation
    # edge1 x edge2 must point along the aim (-Z local): Y x X = -Z.
    edge1 = rot.multVec(FreeCAD.Vector(0, float(obj.Length), 0))
    edge2 = rot.multVec(FreeCAD.Vector(float(obj.Width), 0, 0))
    corner = placement.Base - edge1 * 0.5 - edge2 * 0.5
    return {"corner": vec_m(corner), "edge1": vec_m(edge1), "edge2": vec_m(edge2)}


def _photometric_keys(obj: Any, placement: Any, aim: FreeCAD.Vector) -> Dict[str, Any]:
    c0 = placement.Rotation.multVec(FreeCAD.Vector(1, 0, 0))
    return {"file": os.path.abspath(str(obj.PhotometricFile)), "position": vec_m(placement.Base),
            "aim": [aim.x, aim.y, aim.z], "rotation_deg": round(c0_rotation_deg(aim, c0), 9)}


def _no_checks(obj: Any) -> List[tuple]:
    return []


@dataclass(frozen=True)
class LuminaireKind:
    """One luminaire type of the workbench: its scene-file ``type``, its 3D symbol, the keys
    of its scene entry besides name, type and flux (docs/scene-format.md), and the checks
    only the document can make. A new type is one row here plus its properties above."""

    scene_type: str
    symbol: Callable[[Any, float], List[Any]]
    keys: Callable[[Any, Any, FreeCAD.Vector], Dict[str, Any]]
    check: Callable[[Any], List[tuple]] = _no_checks
    aimed: bool = True  # draws an aim line (not for isotropic emitters)


#: The luminaire types by their ``LuminaireType`` name, in the property's order.
KINDS: Dict[str, LuminaireKind] = {
    "Point": LuminaireKind("point", _sphere, _point_keys, aimed=False),
    "Spot": LuminaireKind("spot", _cone, _spot_keys),
    "Area": LuminaireKind("area", _panel, _area_keys, _check_area),
    "Photometric": LuminaireKind("photometric", _drum, _photometric_keys, _check_photometric),
}


def kind_of(obj: Any) -> LuminaireKind:
    """The row of the luminaire's type (ValueError naming the luminaire for an unknown one)."""
    try:
        return KINDS[obj.LuminaireType]
    except KeyError:
        raise ValueError(f"Luminaire '{obj.Label}': unknown type {obj.LuminaireType!r} "
                         f"(expected {', '.join(KINDS)})") from None


#: The ``LuminaireType`` choices: the table's rows.
LUMINAIRE_TYPES = tuple(KINDS)


class Luminaire(BaseProxy):
    """Point (isotropic), spot (CIE beam/field angles), area (one-sided Lambertian rectangle)
    or photometric (IES/LDT file) luminaire. Position = ``Placement.Base``; aim =
    ``Placement.Rotation`` applied to -Z; a photometric file's C0 plane lies along local +X.

    The exported flux is the maintained flux: ``FluxLumen * MaintenanceFactor``, so the solver
    reports maintained illuminance Em (EN 12464-1)."""

    TYPE = TYPE
    PROPERTIES = {
        "LuminaireType": Prop("App::PropertyEnumeration", "Luminaire",
                              "Emission model: Point (isotropic), Spot (beam/field angles), "
                              "Area (Lambertian rectangle Width x Length facing the aim), "
                              "Photometric (IES LM-63 / EULUMDAT file)",
                              "Area", items=LUMINAIRE_TYPES),
        "FluxLumen": Prop("App::PropertyFloat", "Luminaire",
                          "Initial luminous flux of the luminaire in lumens (lm); 0 = switched "
                          "off, except Photometric: 0 = the file's rated lamp lumens", 3000.0),
        "MaintenanceFactor": Prop("App::PropertyFloat", "Luminaire",
                                  "Maintenance factor MF = LLMF*LSF*LMF*RSMF (0..1]; the solver "
                                  "gets FluxLumen*MF, so results are maintained values", 0.8),
        "ControlGroup": Prop("App::PropertyString", "Luminaire",
                             "Control group (light scene channel): luminaires with the same "
                             "group are switched and dimmed together by light scenes; empty = "
                             "the layout's group for a layout's luminaires, else its own", ""),
        "BeamAngle": Prop("App::PropertyAngle", "Spot",
                          "Spot: full angle where the intensity falls to 50 % of the peak", 40.0),
        "FieldAngle": Prop("App::PropertyAngle", "Spot",
                           "Spot: full angle where the intensity falls to 10 % of the peak", 70.0),
        "Width": Prop("App::PropertyLength", "Area",
                      "Area: luminous width along the local X axis", 600.0),
        "Length": Prop("App::PropertyLength", "Area",
                       "Area: luminous length along the local Y axis", 600.0),
        "PhotometricFile": Prop("App::PropertyFile", "Photometric",
                                "IES LM-63 (.ies) or EULUMDAT (.ldt) file; gamma = 0 along the "
                                "aim, C0 along the luminaire's local X axis"),
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
        kind = kind_of(obj)
        shapes: List[Any] = kind.symbol(obj, size)
        if kind.aimed:
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
