# SPDX-License-Identifier: LGPL-2.1-or-later
"""Material mapping: FreeCAD/Arch objects -> scene materials (docs/scene-format.md).

Priority for each face:
1. a ``Reflectance`` (diffuse) or ``Transmittance`` (glass) property on the object;
2. its Arch material (or the matching entry of an Arch multi-material): a ``Reflectance`` /
   ``Transmittance`` property of the material object or key of its ``Material`` dictionary
   (``"0.7"``, ``"70 %"``);
3. defaults per IFC type: walls 0.5; slabs, roofs, stairs and plain Part solids by face
   orientation (faces down = ceiling 0.7, faces up = floor 0.2, others = wall 0.5);
   window/door glass panels = glass with a light transmittance of 0.9, frames 0.5;
   furniture 0.5.

Transmittance here is the pane's total normal light transmittance (what data sheets give).
The scene's glass ``transmittance`` is the internal transmittance of one pass, so it is
derived: T = tau*(1-R)^2 / (1 - R^2*tau^2) with R = ((n-1)/(n+1))^2. Glass faces that belong to
no solid get ``"thin": true`` (a single-face pane); glass solids stay solid bodies."""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any, Dict, Optional, Tuple

from lighting.compat import get_property, has_property, ifc_type
from lighting.export import defaults

_SOLVER_DEFAULTS = defaults.material_defaults()
#: The solver's glass refractive index and diffuse reflectance (lightsolver/defaults.hpp).
GLASS_IOR = float(_SOLVER_DEFAULTS["glass"]["ior"])
DIFFUSE_REFLECTANCE = float(_SOLVER_DEFAULTS["diffuse"]["reflectance"])
#: Workbench defaults by role (IFC type, face orientation), not the solver's.
DEFAULT_REFLECTANCE = {"ceiling": 0.7, "wall": 0.5, "floor": 0.2, "frame": 0.5,
                       "furniture": 0.5}
DEFAULT_GLASS_TRANSMITTANCE = 0.9

#: IFC types whose faces all count as walls.
WALL_TYPES = {"wall", "curtainwall", "column", "beam", "member", "plate", "railing", "door"}
#: IFC types of furniture.
FURNITURE_TYPES = {"furniture", "furnishingelement", "systemfurnitureelement", "equipment"}
#: IFC types with glass panels among their parts.
WINDOW_TYPES = {"window", "door"}


@dataclass(frozen=True)
class MaterialSpec:
    """A scene material: ``kind`` "diffuse" or "glass" and its parameters."""

    name: str
    kind: str = "diffuse"
    reflectance: float = DIFFUSE_REFLECTANCE
    transmittance: float = 1.0  # light (total) transmittance of a pane, for glass
    thin: bool = False
    ior: float = GLASS_IOR

    def with_thin(self, thin: bool) -> "MaterialSpec":
        """The same glass as a single-face pane (thin) or a solid body."""
        if self.kind != "glass" or self.thin == thin:
            return self
        base = self.name[:-5] if self.name.endswith("_thin") else self.name
        return MaterialSpec(base + ("_thin" if thin else ""), "glass", self.reflectance,
                            self.transmittance, thin, self.ior)

    def scene_entry(self) -> Dict[str, Any]:
        """The ``materials`` value of the scene."""
        if self.kind == "glass":
            return {"type": "glass", "ior": self.ior,
                    "transmittance": internal_transmittance(self.transmittance, self.ior),
                    "thin": self.thin}
        return {"type": "diffuse", "reflectance": self.reflectance}


def internal_transmittance(light_transmittance: float, ior: float = GLASS_IOR) -> float:
    """Internal transmittance tau of one pass giving a pane's total normal transmittance T.

    Solves T = tau*(1-R)^2 / (1 - R^2*tau^2); clamped to [0, 1] (T above the lossless slab's
    (1-R)/(1+R), 0.918 for n = 1.52, is not reachable)."""
    t = min(max(light_transmittance, 0.0), 1.0)
    if t == 0.0:
        return 0.0
    r = ((ior - 1.0) / (ior + 1.0)) ** 2
    if r == 0.0:
        return t
    a, b = t * r * r, (1.0 - r) ** 2
    tau = (-b + math.sqrt(b * b + 4.0 * a * t)) / (2.0 * a)
    return min(max(tau, 0.0), 1.0)


def max_light_transmittance(ior: float = GLASS_IOR) -> float:
    """Total transmittance of a lossless pane, (1-R)/(1+R)."""
    r = ((ior - 1.0) / (ior + 1.0)) ** 2
    return (1.0 - r) / (1.0 + r)


def _sanitize(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", text).strip("_") or "material"


def parse_fraction(value: Any) -> Optional[float]:
    """A reflectance/transmittance from a number or text ("0.7", "70 %", "70"); None if not."""
    if value is None:
        return None
    if isinstance(value, (int, float)):
        number = float(value)
    else:
        match = re.match(r"\s*([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(%?)", str(value))
        if not match:
            return None
        number = float(match.group(1))
        if match.group(2):
            number /= 100.0
    if number > 1.0 and number <= 100.0:
        number /= 100.0
    return number if 0.0 <= number <= 1.0 else None


def default_material(role: str) -> MaterialSpec:
    """The default material of a role: ceiling, wall, floor, frame, furniture or glass."""
    if role == "glass":
        return MaterialSpec("default_glass", "glass", transmittance=DEFAULT_GLASS_TRANSMITTANCE)
    return MaterialSpec(f"default_{role}", "diffuse", DEFAULT_REFLECTANCE[role])


def _from_values(name: str, reflectance: Any, transmittance: Any) -> Optional[MaterialSpec]:
    t = parse_fraction(transmittance)
    if t is not None and t > 0.0:
        return MaterialSpec(_sanitize(name), "glass", transmittance=t)
    r = parse_fraction(reflectance)
    if r is not None:
        return MaterialSpec(_sanitize(name), "diffuse", r)
    return None


def object_property_material(obj: Any) -> Optional[MaterialSpec]:
    """Material from ``Reflectance`` / ``Transmittance`` properties on the object itself."""
    if not (has_property(obj, "Reflectance") or has_property(obj, "Transmittance")):
        return None
    return _from_values(f"{obj.Name}_material", get_property(obj, "Reflectance"),
                        get_property(obj, "Transmittance"))


def arch_material(material_obj: Any) -> Optional[MaterialSpec]:
    """Material from an Arch material object (property or ``Material`` dictionary keys)."""
    if material_obj is None:
        return None
    table: Dict[str, Any] = {}
    raw = get_property(material_obj, "Material")
    if isinstance(raw, dict):
        table = {k.replace(" ", "").lower(): v for k, v in raw.items()}
    reflectance = get_property(material_obj, "Reflectance",
                               table.get("reflectance", table.get("lightreflectance")))
    transmittance = get_property(material_obj, "Transmittance",
                                 table.get("transmittance", table.get("lighttransmittance")))
    return _from_values(f"arch_{material_obj.Label}", reflectance, transmittance)


def is_multi_material(material_obj: Any) -> bool:
    """True for an Arch multi-material (layers or window parts)."""
    return has_property(material_obj, "Materials") and has_property(material_obj, "Names")


def multi_material_entry(material_obj: Any, part_name: Optional[str] = None,
                         index: Optional[int] = None) -> Optional[MaterialSpec]:
    """The material of a multi-material entry, matched by name (window part) or index."""
    names = list(material_obj.Names)
    mats = list(material_obj.Materials)
    chosen = None
    if part_name is not None and part_name in names:
        chosen = mats[names.index(part_name)]
    elif index is not None and index < len(mats):
        chosen = mats[index]
    return arch_material(chosen) if chosen is not None else None


def orientation_role(normal_z: float) -> str:
    """Role of a face from its outward normal's z: ceiling (down), floor (up) or wall."""
    if normal_z < -0.5:
        return "ceiling"
    if normal_z > 0.5:
        return "floor"
    return "wall"


def default_role(obj: Any, normal_z: float, part_kind: Optional[str]) -> str:
    """Default role of a face of ``obj`` (part_kind "glass"/"frame" for window parts)."""
    kind = ifc_type(obj)
    if part_kind == "glass":
        return "glass"
    if part_kind == "frame" or kind in WINDOW_TYPES:
        return "frame"
    if kind in WALL_TYPES:
        return "wall"
    if kind in FURNITURE_TYPES or obj.isDerivedFrom("Mesh::Feature"):
        return "furniture"
    return orientation_role(normal_z)


class MaterialResolver:
    """Resolves and collects the materials of an export; one instance per export."""

    def __init__(self) -> None:
        self.materials: Dict[str, MaterialSpec] = {}
        self.notes: list = []

    def _register(self, spec: MaterialSpec) -> MaterialSpec:
        existing = self.materials.get(spec.name)
        if existing is not None and existing != spec:
            index = 2
            while f"{spec.name}_{index}" in self.materials and \
                    self.materials[f"{spec.name}_{index}"] != spec:
                index += 1
            spec = MaterialSpec(f"{spec.name}_{index}", spec.kind, spec.reflectance,
                                spec.transmittance, spec.thin, spec.ior)
        if spec.kind == "glass" and spec.transmittance > max_light_transmittance(spec.ior) + 1e-9:
            self.notes.append(f"material '{spec.name}': light transmittance "
                              f"{spec.transmittance:g} exceeds a clear pane's "
                              f"{max_light_transmittance(spec.ior):.3f}; using lossless glass")
        self.materials[spec.name] = spec
        return spec

    def resolve(self, obj: Any, normal_z: float, part_kind: Optional[str] = None,
                part_name: Optional[str] = None, solid_index: Optional[int] = None,
                in_solid: bool = True) -> MaterialSpec:
        """The material of one face of ``obj``; registers it in ``materials``."""
        spec = object_property_material(obj)
        if spec is None:
            mat = get_property(obj, "Material")
            if mat is not None:
                if is_multi_material(mat):
                    spec = multi_material_entry(mat, part_name, solid_index)
                else:
                    spec = arch_material(mat)
        if spec is None:
            spec = default_material(default_role(obj, normal_z, part_kind))
        if spec.kind == "glass":
            spec = spec.with_thin(not in_solid)
        return self._register(spec)

    def scene_materials(self) -> Dict[str, Dict[str, Any]]:
        """The scene's ``materials`` object."""
        return {name: spec.scene_entry() for name, spec in sorted(self.materials.items())}


def window_part_kinds(obj: Any) -> Tuple[Tuple[str, str], ...]:
    """(part name, "glass" | "frame") for each window part that yields a shape, in order."""
    parts = list(get_property(obj, "WindowParts", []) or [])
    result = []
    for i in range(len(parts) // 5):
        name, kind, wires = parts[5 * i], parts[5 * i + 1], parts[5 * i + 2]
        if "Wire" not in wires:
            continue
        result.append((name, "glass" if kind == "Glass panel" else "frame"))
    return tuple(result)
