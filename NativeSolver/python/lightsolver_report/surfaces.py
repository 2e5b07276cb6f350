# SPDX-License-Identifier: LGPL-2.1-or-later
"""The surfaces of the model and their materials, listed surface by surface as the scene states
them: each object (named by its label) with the material of each of its parts, and which faces
each part covers (top, underside, sides: from the part's own triangles).

Why by surface: the workbench exports an object whose faces carry different materials as one
mesh per material (``Structure.default_floor``, ``Structure.default_ceiling``...), so a floor
slab's underside carries the ceiling material and a ceiling slab's top the floor material. A
table by material then reads "floor material: Floor, Ceiling"; by surface it reads "Ceiling:
underside ceiling material, top floor material", which is what the model says."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence

import numpy as np

from lightsolver_report.fmt import finite

#: Share of a part's area a face orientation needs before it is named (smaller slivers of a
#: tessellation are not worth a word).
_NAMED_SHARE = 0.05


@dataclass
class MaterialRow:
    """A material with its factors (the solver's defaults filled in)."""

    name: str
    type: str
    reflectance: Optional[float] = None
    specular: Optional[float] = None
    roughness: Optional[float] = None
    transmittance: Optional[float] = None
    ior: Optional[float] = None
    thin: Optional[bool] = None
    #: The surfaces using it, by label (kept for scripts; the page lists by surface).
    used_by: List[str] = field(default_factory=list)


@dataclass
class SurfacePart:
    """One material of a surface and the faces it covers ("top", "underside", "sides", or
    "" where not known: geometry in a mesh file)."""

    faces: str
    material: MaterialRow
    area_m2: Optional[float] = None


@dataclass
class SurfaceRow:
    """A surface of the model (an object, by its label) and the materials of its parts."""

    label: str
    parts: List[SurfacePart] = field(default_factory=list)
    #: A calculation surface (a surface target's mesh), not a part of the building.
    calculation: bool = False


def _materials(scene: Dict[str, Any],
               defaults: Optional[Dict[str, Dict[str, Any]]]) -> Dict[str, MaterialRow]:
    rows: Dict[str, MaterialRow] = {}
    for name, mat in (scene.get("materials") or {}).items():
        mat = mat if isinstance(mat, dict) else {}
        kind = str(mat.get("type", "diffuse"))
        values = dict((defaults or {}).get(kind, {}))
        values.update({k: v for k, v in mat.items() if k != "type"})
        rows[str(name)] = MaterialRow(
            name=str(name), type=kind, reflectance=finite(values.get("reflectance")),
            specular=finite(values.get("specular")), roughness=finite(values.get("roughness")),
            transmittance=finite(values.get("transmittance")), ior=finite(values.get("ior")),
            thin=values.get("thin") if kind == "glass" else None)
    return rows


def _triangle_normals(mesh: Dict[str, Any]) -> Optional[np.ndarray]:
    """Area-weighted normals (the cross products, |n| = 2 area) of an inline mesh, with its
    transform applied; None for a mesh file or unreadable geometry."""
    try:
        v = np.asarray(mesh["vertices"], dtype=float).reshape(-1, 3)
        t = np.asarray(mesh["triangles"], dtype=np.int64).reshape(-1, 3)
        if t.size == 0 or t.min() < 0 or t.max() >= len(v):
            return None
        transform = mesh.get("transform")
        if transform is not None:
            m = np.asarray(transform, dtype=float).reshape(4, 4)
            v = v @ m[:3, :3].T + m[:3, 3]
    except (KeyError, TypeError, ValueError):
        return None
    return np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]])


def faces_of(mesh: Dict[str, Any]) -> tuple:
    """("top, sides", area m²) of an inline mesh: the orientations its front faces cover
    (normal up, down, or across), by area; ("", None) for a mesh file."""
    normals = _triangle_normals(mesh)
    if normals is None:
        return "", None
    twice_area = np.linalg.norm(normals, axis=1)
    total = float(twice_area.sum())
    if total <= 0:
        return "", 0.0
    nz = np.divide(normals[:, 2], twice_area, out=np.zeros(len(twice_area)),
                   where=twice_area > 0)
    shares = {"top": twice_area[nz > 0.5].sum(), "underside": twice_area[nz < -0.5].sum(),
              "sides": twice_area[np.abs(nz) <= 0.5].sum()}
    named = [k for k, a in shares.items() if a / total >= _NAMED_SHARE]
    return ", ".join(named), 0.5 * total


def build_surfaces(scene: Dict[str, Any], defaults: Optional[Dict[str, Dict[str, Any]]]
                   ) -> tuple:
    """(surfaces, materials): every surface by its label, its parts with their materials (in
    scene order), and every material with the surfaces using it (materials no surface uses
    included: the page says so)."""
    meta = scene.get("metadata") if isinstance(scene.get("metadata"), dict) else {}
    labels = meta.get("labels") if isinstance(meta.get("labels"), dict) else {}
    materials = _materials(scene, defaults)
    measured = {str(t.get("mesh")) for t in scene.get("targets", [])
                if isinstance(t, dict) and t.get("type", "surface") == "surface"}
    surfaces: Dict[str, SurfaceRow] = {}
    for mesh in scene.get("meshes", []):
        if not isinstance(mesh, dict):
            continue
        name = str(mesh.get("name", ""))
        obj = name.split(".", 1)[0]
        label = str(labels.get(name, labels.get(obj, name)))
        row = surfaces.setdefault(label, SurfaceRow(label, calculation=name in measured))
        row.calculation = row.calculation and name in measured
        material = materials.get(str(mesh.get("material", "")))
        if material is None:  # the solver refuses such a scene; the page shows the name
            material = materials.setdefault(str(mesh.get("material")),
                                            MaterialRow(str(mesh.get("material")), "unknown"))
        faces, area = faces_of(mesh)
        row.parts.append(SurfacePart(faces, material, area))
        if label not in material.used_by:
            material.used_by.append(label)
    for row in surfaces.values():
        if len(row.parts) == 1:
            row.parts[0].faces = "all faces"
    return list(surfaces.values()), list(materials.values())


def unused(materials: Sequence[MaterialRow]) -> List[MaterialRow]:
    """Materials no surface uses."""
    return [m for m in materials if not m.used_by]
