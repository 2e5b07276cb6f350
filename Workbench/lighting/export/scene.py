# SPDX-License-Identifier: LGPL-2.1-or-later
"""Build and write the scene (docs/scene-format.md, ``lightsolver.scene/1``) of an analysis.

Geometry: every exported object (see :mod:`lighting.export.collect`) is tessellated with
the analysis' deflection, converted to metres and split into one mesh per material. Faces
of face targets go into the target's own mesh instead (front = outward face normal), so the
target is exactly those faces and no geometry is doubled."""
from __future__ import annotations

import json
import os
import re
import tempfile
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Tuple

import FreeCAD

from lighting import __version__, files
from lighting.export import collect, daylight, defaults, ply
from lighting.export.materials import MaterialResolver, MaterialSpec, window_part_kinds
from lighting.export.tessellate import (FaceTriangles, MeshBuilder, largest_triangle,
                                        mesh_triangles, tessellate_faces, triangle_normal)
from lighting.geometry import face_normal, global_placement, global_shape, referenced_faces
from lighting.messages import ExportError, Report
from lighting.objects import analysis as analysis_mod
from lighting.objects import luminaire as luminaire_mod
from lighting.objects import luminaire_layout as layout_mod
from lighting.objects import observer as observer_mod
from lighting.objects import placement_domain as domain_mod
from lighting.objects import target as target_mod

FORMAT = defaults.scene_format()
SCENE_FILE = "scene.json"
RESULTS_FILE = "results.json"
INLINE_LIMIT_TRIANGLES = 20000

Progress = Optional[Callable[[str], None]]


@dataclass
class ExportResult:
    """A built scene and what the export found on the way."""

    scene: Dict[str, Any]
    report: Report
    scene_file: Optional[str] = None
    mesh_triangles: Dict[str, int] = field(default_factory=dict)
    object_meshes: Dict[str, List[str]] = field(default_factory=dict)

    @property
    def triangle_count(self) -> int:
        """Triangles in the whole scene."""
        return sum(self.mesh_triangles.values())


def _face_parts(obj: Any, shape: Any, report: Report) -> Dict[int, Tuple[str, Optional[str], int]]:
    """face hash -> (part kind, part name, solid index) for windows and multi-material objects."""
    mapping: Dict[int, Tuple[str, Optional[str], int]] = {}
    kinds = window_part_kinds(obj)
    if kinds:
        children = shape.childShapes() if shape.ShapeType == "Compound" else [shape]
        children = [c for c in children if c.Faces]
        if len(children) == len(kinds):
            for (name, kind), child in zip(kinds, children):
                for face in child.Faces:
                    mapping[face.hashCode()] = (kind, name, -1)
            return mapping
        report.add("warning", f"'{obj.Label}': window parts do not match its shape; faces that "
                              "belong to no solid are taken as glass, the rest as frame", obj.Name)
        for child in children:
            kind = "frame" if child.Solids else "glass"
            for face in child.Faces:
                mapping[face.hashCode()] = (kind, None, -1)
        return mapping
    for index, solid in enumerate(shape.Solids):
        for face in solid.Faces:
            mapping.setdefault(face.hashCode(), ("", None, index))
    return mapping


def _outward_flip(face: Any, part: FaceTriangles, solids: List[Any]) -> bool:
    """True when the triangles of a target face point into their solid (flip them)."""
    if not solids or not part.triangles:
        return False
    centre, normal = triangle_normal(part, largest_triangle(part))
    if normal.Length == 0:
        return False
    probe = centre + normal.normalize() * 0.5
    for solid in solids:
        try:
            if any(f.isSame(face) for f in solid.Faces):
                return bool(solid.isInside(probe, 0.01, True))
        except Exception:  # noqa: BLE001 - keep OCC's orientation
            return False
    return False


class SceneBuilder:
    """Collects meshes, targets and luminaires of one analysis."""

    def __init__(self, analysis: Any, progress: Progress = None) -> None:
        self.analysis = analysis
        self.doc = analysis.Document
        self.progress = progress
        self.report = Report()
        self.resolver = MaterialResolver()
        self.linear_mm = float(analysis.LinearDeflection)
        self.angular_deg = float(analysis.AngularDeflection)
        self.object_builders: Dict[str, Dict[str, MeshBuilder]] = {}
        self.target_builders: Dict[str, MeshBuilder] = {}
        self.owner: Dict[Tuple[str, int], Any] = {}
        self.labels: Dict[str, str] = {}

    # -- face targets ----------------------------------------------------------------------
    def _claim_target_faces(self, targets: List[Any]) -> None:
        for tgt in targets:
            if tgt.TargetType != "Faces":
                continue
            try:
                faces = referenced_faces(tgt.References)
            except ValueError as exc:
                self.report.add("error", f"Target '{tgt.Label}': {exc}", tgt.Name)
                continue
            for obj, index, _ in faces:
                key = (obj.Name, index)
                if key in self.owner and self.owner[key].Name != tgt.Name:
                    self.report.add("error", f"'{obj.Label}.Face{index + 1}' is in targets "
                                             f"'{self.owner[key].Label}' and '{tgt.Label}'; a "
                                             "face can belong to one target only", tgt.Name)
                self.owner[key] = tgt

    def _target_builder(self, tgt: Any, spec: MaterialSpec) -> MeshBuilder:
        builder = self.target_builders.get(tgt.Name)
        if builder is None:
            builder = MeshBuilder(f"{tgt.Name}.faces", spec.name)
            self.target_builders[tgt.Name] = builder
        elif builder.material != spec.name:
            self.report.add("warning", f"Target '{tgt.Label}' spans faces of different materials; "
                                       f"all its faces use '{builder.material}'", tgt.Name)
        return builder

    # -- objects ---------------------------------------------------------------------------
    def _builder(self, obj: Any, spec: MaterialSpec) -> MeshBuilder:
        per_object = self.object_builders.setdefault(obj.Name, {})
        builder = per_object.get(spec.name)
        if builder is None:
            builder = MeshBuilder(obj.Name, spec.name)
            per_object[spec.name] = builder
        return builder

    def add_mesh_object(self, obj: Any) -> None:
        """A Mesh::Feature: one mesh, one material (furniture default)."""
        mesh = obj.Mesh.copy()
        mesh.Placement = global_placement(obj)
        spec = self.resolver.resolve(obj, 0.0, in_solid=True)
        self._builder(obj, spec).add(mesh_triangles(mesh))

    def add_shape_object(self, obj: Any, claimed_only: bool = False) -> None:
        """A Part-based object: per-face materials, target faces routed to their targets."""
        try:
            shape = global_shape(obj)
        except Exception as exc:  # noqa: BLE001
            self.report.add("warning", f"'{obj.Label}' has no usable shape ({exc}); left out",
                            obj.Name)
            return
        try:
            parts, errors = tessellate_faces(shape, self.linear_mm, self.angular_deg)
        except Exception as exc:  # noqa: BLE001 - a broken B-rep must not stop the export
            parts, errors = [None] * len(shape.Faces), [f"{type(exc).__name__}: {exc}"]
        failed = sum(1 for p in parts if p is None)
        if errors:
            level = "warning"
            what = "left out" if failed == len(parts) else f"{failed} face(s) left out"
            self.report.add(level, f"'{obj.Label}' failed to tessellate: {errors[0]} ({what})",
                            obj.Name)
        face_parts = _face_parts(obj, shape, self.report)
        solid_faces = {f.hashCode() for s in shape.Solids for f in s.Faces}
        for index, face in enumerate(shape.Faces):
            part = parts[index]
            tgt = self.owner.get((obj.Name, index))
            if part is None or (claimed_only and tgt is None):
                continue
            kind, name, solid_index = face_parts.get(face.hashCode(), ("", None, -1))
            spec = self.resolver.resolve(obj, face_normal(face).z, kind or None, name,
                                         solid_index if solid_index >= 0 else None,
                                         in_solid=face.hashCode() in solid_faces)
            if tgt is not None:
                flip = _outward_flip(face, part, shape.Solids)
                self._target_builder(tgt, spec).add(part, flip=flip)
            else:
                self._builder(obj, spec).add(part)

    # -- scene ---------------------------------------------------------------------------
    def _say(self, text: str) -> None:
        if self.progress is not None:
            self.progress(text)

    def build(self) -> ExportResult:
        """Build the scene dictionary (meshes inline)."""
        # Luminaire objects and the members of layouts (a layout's template is not placed).
        lums = layout_mod.placed_luminaires(self.analysis, self.report)
        tgts = analysis_mod.targets(self.analysis)
        sky = daylight.build(self.analysis, self.report)
        if not lums and not sky.luminaires:
            self.report.add("error", "No luminaires: add at least one with Lighting > Luminaire")
        if not tgts:
            self.report.add("error", "No targets: add a face target or a calculation grid")
        self._claim_target_faces(tgts)
        # Windows that became a sky's portals: the portal's glazing stands for them.
        exported = [o for o in collect.exported_objects(self.doc)
                    if o.Name not in sky.replaced_windows]
        exported_names = {o.Name for o in exported}
        for number, obj in enumerate(exported, 1):
            self._say(f"Tessellating {obj.Label} ({number}/{len(exported)})")
            self.labels[obj.Name] = obj.Label
            if collect.is_mesh(obj):
                self.add_mesh_object(obj)
            else:
                self.add_shape_object(obj)
        # Faces of targets on objects that are not exported (excluded or consumed): the
        # target's own geometry is still needed.
        for obj_name in sorted({k[0] for k in self.owner} - exported_names):
            obj = self.doc.getObject(obj_name)
            self.report.add("warning", f"Targets use faces of '{obj.Label}', which is excluded "
                                       "or consumed; only those faces are exported", obj_name)
            self.add_shape_object(obj, claimed_only=True)
        meshes: List[Dict[str, Any]] = []
        result = ExportResult(scene={}, report=self.report)
        for obj_name, per_material in self.object_builders.items():
            builders = [b for b in per_material.values() if b.triangles]
            for builder in builders:
                if len(builders) > 1:
                    builder.name = f"{obj_name}.{builder.material}"
                meshes.append(builder.scene_entry())
                result.mesh_triangles[builder.name] = len(builder.triangles)
                result.object_meshes.setdefault(obj_name, []).append(builder.name)
        targets: List[Dict[str, Any]] = []
        for tgt in tgts:
            self.labels[tgt.Name] = tgt.Label
            if tgt.TargetType == "Grid":
                try:
                    targets.append(dict(target_mod.grid_rectangle(tgt).scene_entry(tgt.Name),
                                        **target_mod.requirements_entry(tgt)))
                except ValueError as exc:
                    self.report.add("error", str(exc), tgt.Name)
                continue
            builder = self.target_builders.get(tgt.Name)
            if builder is None or not builder.triangles:
                self.report.add("error", f"Target '{tgt.Label}' has no exportable faces", tgt.Name)
                continue
            meshes.append(builder.scene_entry())
            result.mesh_triangles[builder.name] = len(builder.triangles)
            targets.append({"name": tgt.Name, "type": "surface", "mesh": builder.name,
                            **target_mod.requirements_entry(tgt)})
        for eye in analysis_mod.observers(self.analysis):
            self.labels[eye.Name] = eye.Label
            targets.append(observer_mod.scene_entry(eye))
        luminaires = []
        for lum in lums:
            self.labels[lum.Name] = lum.Label
            try:
                luminaires.append(luminaire_mod.scene_entry(lum))
            except (OSError, ValueError) as exc:
                self.report.add("error", f"Luminaire '{lum.Label}': {exc}",
                                layout_mod.report_name(lum))
        luminaires.extend(sky.luminaires)
        self.labels.update(sky.labels)
        for note in self.resolver.notes:
            self.report.add("warning", note)
        dropped = sum(b.dropped for per in self.object_builders.values() for b in per.values())
        if dropped:
            self.report.add("info", f"{dropped} degenerate triangle(s) dropped")
        result.scene = {
            "format": FORMAT,
            "materials": self.resolver.scene_materials(),
            "meshes": meshes,
            "luminaires": luminaires,
            "targets": targets,
            "settings": analysis_mod.settings(self.analysis),
            "metadata": self._metadata(lums),
        }
        if sky.north_deg is not None:
            result.scene["metadata"]["north_deg"] = sky.north_deg
        if sky.sunlight is not None:
            result.scene["sunlight_exposure"] = sky.sunlight
        return result

    def _metadata(self, lums: List[Any]) -> Dict[str, Any]:
        domains = []
        for domain in analysis_mod.placement_domains(self.analysis):
            try:
                domains.append(domain_mod.metadata_entry(domain))
            except ValueError as exc:
                self.report.add("warning", str(exc), domain.Name)
        return {
            "generator": f"FreeCAD Lighting workbench {__version__}",
            "freecad_version": ".".join(FreeCAD.Version()[:3]),
            "document": self.doc.Name,
            "document_file": self.doc.FileName,
            "analysis": self.analysis.Name,
            "units": "metres, lumens, lux",
            "backend": self.analysis.Backend,
            "target_accuracy": float(self.analysis.TargetAccuracy),
            "labels": self.labels,
            "luminaires": {lum.Name: {"flux_lm_initial": float(lum.FluxLumen),
                                      "maintenance_factor": float(lum.MaintenanceFactor)}
                           for lum in lums},
            "placement_domains": domains,
            "luminaire_layouts": {layout.Name: [m.Name for m in lums
                                                if getattr(m, "layout", None) is layout]
                                  for layout in layout_mod.layouts(self.analysis)},
            # The analysis' light scenes, for the report's light-scene pages (docs/report.md);
            # a scene whose levels do not pair up is left out (Check names it).
            "light_scenes": self._light_scenes(),
        }

    def _light_scenes(self) -> List[Dict[str, Any]]:
        from lighting.objects import light_scene

        found = []
        for scene in light_scene.scenes(self.analysis):
            try:
                found.append({"name": scene.Label, "levels": light_scene.levels(scene)})
            except ValueError:
                continue
        return found


def build_scene(analysis: Any, progress: Progress = None) -> ExportResult:
    """The scene of ``analysis`` in memory (meshes inline) and the export's report."""
    return SceneBuilder(analysis, progress).build()


def default_output_directory(analysis: Any) -> str:
    """``OutputDirectory`` or '<document>_lighting/<analysis>' next to the saved document, or a
    folder in the temporary directory for unsaved documents."""
    if analysis.OutputDirectory:
        return str(analysis.OutputDirectory)
    doc = analysis.Document
    if doc.FileName:
        stem = os.path.splitext(os.path.basename(doc.FileName))[0]
        return os.path.join(os.path.dirname(doc.FileName), f"{stem}_lighting", analysis.Name)
    return os.path.join(tempfile.gettempdir(), f"lighting-{doc.Name}", analysis.Name)


def _safe_file_name(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name)


def dumps_scene(scene: Dict[str, Any]) -> str:
    """JSON text, indented, with each mesh's vertex and triangle arrays on one line."""
    arrays: Dict[str, str] = {}
    shallow = dict(scene)
    shallow["meshes"] = []
    for i, mesh in enumerate(scene.get("meshes", [])):
        entry = dict(mesh)
        for key in ("vertices", "triangles"):
            if key in entry:
                token = f"@@mesh{i}.{key}@@"
                arrays[f'"{token}"'] = json.dumps(entry[key], separators=(",", ":"))
                entry[key] = token
        shallow["meshes"].append(entry)
    text = json.dumps(shallow, indent=2)
    for token, value in arrays.items():
        text = text.replace(token, value, 1)
    return text + "\n"


def _copy_photometry(luminaire: Dict[str, Any], directory: str) -> Dict[str, Any]:
    """Photometric files are copied next to the scene (``photometry/``), so the scene folder
    is self-contained; the entry then names the copy relative to the scene file."""
    source = luminaire.get("file")
    if not source or not os.path.isabs(source):
        return luminaire
    rel = f"photometry/{_safe_file_name(luminaire['name'])}_{os.path.basename(source)}"
    os.makedirs(os.path.join(directory, "photometry"), exist_ok=True)
    files.copy_file(source, os.path.join(directory, rel))
    return dict(luminaire, file=rel)


def write_scene(result: ExportResult, directory: str, storage: str = "Auto") -> str:
    """Write ``scene.json`` (and ``meshes/*.ply`` for PLY storage) into ``directory``."""
    try:
        files.check_folder(directory, "scene folder")
        scene = dict(result.scene)
        use_ply = storage == "PLY" or (storage == "Auto" and
                                       result.triangle_count > INLINE_LIMIT_TRIANGLES)
        if use_ply:
            os.makedirs(os.path.join(directory, "meshes"), exist_ok=True)
            meshes = []
            for mesh in scene["meshes"]:
                rel = f"meshes/{_safe_file_name(mesh['name'])}.ply"
                ply.write_ply(os.path.join(directory, rel), mesh["vertices"], mesh["triangles"])
                meshes.append({"name": mesh["name"], "material": mesh["material"], "file": rel})
            scene["meshes"] = meshes
        scene["luminaires"] = [_copy_photometry(lum, directory) for lum in scene["luminaires"]]
        path = os.path.join(directory, SCENE_FILE)
        files.write_text(path, dumps_scene(scene))
    except OSError as exc:
        raise ExportError(f"Cannot write the scene to '{directory}': {exc}") from exc
    result.scene_file = path
    return path


def export_scene(analysis: Any, directory: Optional[str] = None, progress: Progress = None,
                 storage: Optional[str] = None) -> ExportResult:
    """Build the scene of ``analysis`` and write it (see :func:`write_scene`)."""
    result = build_scene(analysis, progress)
    write_scene(result, directory or default_output_directory(analysis),
                storage or analysis.MeshStorage)
    return result
