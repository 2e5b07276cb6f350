# SPDX-License-Identifier: LGPL-2.1-or-later
"""Check stage: is the model ready for an analysis?

Two halves. What the document alone knows is checked here: no luminaires or targets,
luminaires inside solids or flush with surfaces, open shells and non-solid meshes, the
objects' own properties (maintenance factor, grid bands, ...). Everything a scene file can
express is checked by the solver's one validator: the scene is exported in memory as for a
run and handed to ``lightsolver.check_scene_json``, whose errors and warnings name the scene
field (``luminaires[0].flux_lm``); they are reported against the object that field came from.
Errors block the run; warnings do not."""
from __future__ import annotations

import json
import os
import re
from typing import Any, Dict, List, Optional, Tuple

import FreeCAD

from lighting.export import collect
from lighting.export import scene as scene_mod
from lighting.geometry import global_placement, global_shape
from lighting.messages import LightingError, Report, SolverUnavailableError
from lighting.objects import analysis as analysis_mod
from lighting.objects import luminaire as luminaire_mod
from lighting.objects import luminaire_layout as layout_mod
from lighting.objects import light_scene as light_scene_mod
from lighting.objects import observer as observer_mod
from lighting.objects import placement_domain as domain_mod
from lighting.objects import target as target_mod
from lighting.solver import run

#: Emitters closer than this to a surface are reported as flush with it.
FLUSH_MM = 0.5
#: Luminaires closer than this to each other are reported as coincident.
COINCIDENT_MM = 10.0


def _emitter_points(lum: Any) -> List[FreeCAD.Vector]:
    """Points of the emitter to test against solids: the centre, and an area's corners."""
    placement = global_placement(lum)
    points = [placement.Base]
    if lum.LuminaireType == "Area":
        rot = placement.Rotation
        hw, hl = float(lum.Width) / 2.0, float(lum.Length) / 2.0
        for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            points.append(placement.Base + rot.multVec(FreeCAD.Vector(sx * hw * 0.99,
                                                                      sy * hl * 0.99, 0)))
    return points


def _check_geometry(report: Report, exported: List[Any]) -> List[tuple]:
    """Open shells, invalid shapes, non-solid meshes; returns (object, shape) pairs."""
    shapes = []
    for obj in exported:
        if collect.is_mesh(obj):
            mesh = obj.Mesh
            if not mesh.isSolid():
                report.add("warning", f"Mesh '{obj.Label}' is not closed (non-solid): light can "
                                      "leak through its holes", obj.Name)
            elif mesh.hasNonManifolds():
                report.add("warning", f"Mesh '{obj.Label}' has non-manifold edges", obj.Name)
            continue
        try:
            shape = global_shape(obj)
        except Exception as exc:  # noqa: BLE001
            report.add("warning", f"'{obj.Label}' has no usable shape ({exc})", obj.Name)
            continue
        try:
            valid = shape.isValid()
        except Exception:  # noqa: BLE001
            valid = False
        if not valid:
            report.add("warning", f"'{obj.Label}' has an invalid shape; it may tessellate badly",
                       obj.Name)
        open_shells = [s for s in shape.Shells if not s.isClosed()]
        in_solids = sum(len(s.Faces) for s in shape.Solids)
        if open_shells:
            report.add("warning", f"'{obj.Label}' has {len(open_shells)} open shell(s) (leaky "
                                  "geometry): light can pass through the gaps", obj.Name)
        elif in_solids < len(shape.Faces) and not shape.Solids:
            report.add("info", f"'{obj.Label}' is a surface without volume (exported as a "
                               "double-sided sheet)", obj.Name)
        shapes.append((obj, shape))
    return shapes


def _check_luminaire_positions(report: Report, lums: List[Any], shapes: List[tuple]) -> None:
    model_box = None
    for _, shape in shapes:
        if model_box is None:
            model_box = FreeCAD.BoundBox(shape.BoundBox)
        else:
            model_box.add(shape.BoundBox)
    for lum in lums:
        points = _emitter_points(lum)
        buried = False
        for obj, shape in shapes:
            for solid in shape.Solids:
                inside = [p for p in points if solid.BoundBox.isInside(p)
                          and solid.isInside(p, 1e-3, False)]
                if inside:
                    report.add("error", f"Luminaire '{lum.Label}' is inside '{obj.Label}': its "
                                        "light would be trapped; move it into the room",
                               lum.Name)
                    buried = True
                    break
            if buried:
                break
        if not buried:
            _check_flush(report, lum, points[0], shapes)
        if model_box is not None and model_box.isValid():
            box = FreeCAD.BoundBox(model_box)
            box.enlarge(5000.0)
            if not box.isInside(points[0]):
                report.add("warning", f"Luminaire '{lum.Label}' is more than 5 m outside the "
                                      "model", lum.Name)


def _check_flush(report: Report, lum: Any, point: FreeCAD.Vector, shapes: List[tuple]) -> None:
    """An emitter lying on a surface is partly blocked by it (coincident geometry)."""
    import Part

    vertex = None
    for obj, shape in shapes:
        box = FreeCAD.BoundBox(shape.BoundBox)
        box.enlarge(FLUSH_MM)
        if not box.isInside(point):
            continue
        vertex = vertex or Part.Vertex(point)
        try:
            distance = shape.distToShape(vertex)[0]
        except Exception:  # noqa: BLE001 - no distance, no warning
            continue
        if distance < FLUSH_MM:
            report.add("warning", f"Luminaire '{lum.Label}' lies on '{obj.Label}' "
                                  f"({distance:.2f} mm): the surface may block its light; move "
                                  "it a few millimetres off", lum.Name)
            return


def _check_coincident(report: Report, lums: List[Any]) -> None:
    """Two luminaires in one spot (within COINCIDENT_MM): a double click, not a design."""
    for first, second, distance in layout_mod.coincident_pairs(lums, COINCIDENT_MM):
        report.add("warning", f"Luminaires '{first.Label}' and '{second.Label}' are at the same "
                              f"point ({distance:.1f} mm apart): one of them is probably placed "
                              "twice; move or delete it", layout_mod.report_name(second))


def _field_objects(export: Any) -> Dict[str, str]:
    """Scene path ("luminaires[2]", "meshes[0]", "targets[1]") -> document object name."""
    owners = {mesh: obj for obj, meshes in export.object_meshes.items() for mesh in meshes}
    scene = export.scene
    out: Dict[str, str] = {}
    for key in ("luminaires", "targets"):
        for i, entry in enumerate(scene.get(key, [])):
            out[f"{key}[{i}]"] = entry["name"]  # exported under the object's Name
    for i, mesh in enumerate(scene.get("meshes", [])):
        out[f"meshes[{i}]"] = owners.get(mesh["name"], mesh["name"].split(".")[0])
    # A problem inside a photometric file names the file (and line), not a field.
    for entry in scene.get("luminaires", []):
        if entry.get("file"):
            out.setdefault(os.path.realpath(entry["file"]), entry["name"])
    return out


def _check_scene_natively(report: Report, analysis: Any) -> Optional[Any]:
    """The solver's validator on the scene a run would export (see the module doc); returns
    that export, so a run's Prepare stage need not tessellate the model again. Skipped without
    the module (``need_solver`` says so; the solver validates again when it runs) and when the
    export itself fails (Prepare reports why)."""
    try:
        module = run.load_module()
    except SolverUnavailableError:
        return None
    check_json = getattr(module, "check_scene_json", None)
    if check_json is None:
        report.add("warning", "This lightsolver build has no scene check (check_scene_json); "
                              "scene values are checked when the solver runs: rebuild it")
        return None
    try:
        export = scene_mod.build_scene(analysis)
    except (LightingError, OSError, ValueError):
        return None
    if not export.report.ok:
        return None
    text = json.dumps(export.scene)
    found = check_json(text, scene_mod.default_output_directory(analysis))
    owners = _field_objects(export)
    labels = {o.Name: o.Label for o in analysis.Document.Objects}
    flagged = {m.object_name for m in report.errors}
    settings_owner = analysis.Name
    for level, issues in (("error", found["errors"]), ("warning", found["warnings"])):
        for issue in issues:
            field = str(issue["field"])
            head = re.match(r"[a-z_]+(\[\d+\])?", field)
            owner = owners.get(head.group(0)) if head else None
            if owner is None and issue["file"]:
                owner = owners.get(os.path.realpath(str(issue["file"])))
            if owner is None and field.startswith("settings"):
                owner = settings_owner
            if level == "error" and owner is not None and owner in flagged:
                continue  # the object's own check already said what is wrong with it
            where = f"'{labels.get(owner, owner)}' " if owner else ""
            located = f"{field}: " if field else ""
            if issue["line"]:
                located = f"{issue['file']}, line {issue['line']}: "
            report.add(level, f"{where}{located}{issue['message']}".strip(), owner)
    return export


def check_analysis(analysis: Any, need_solver: bool = True,
                   exported: Optional[List[Any]] = None) -> Report:
    """All checks of an analysis; ``need_solver`` adds an error when ``lightsolver`` is
    missing."""
    return check_and_export(analysis, need_solver, exported)[0]


def check_and_export(analysis: Any, need_solver: bool = True,
                     exported: Optional[List[Any]] = None) -> Tuple[Report, Optional[Any]]:
    """check_analysis, and the scene export its native check made (None when it made none):
    the run's Prepare stage writes that one instead of exporting the model a second time."""
    report = Report()
    report.extend(analysis_mod.check(analysis), analysis.Name)
    lums = analysis_mod.luminaires(analysis)
    placed = layout_mod.placed_luminaires(analysis)  # layout members in, their templates out
    tgts = analysis_mod.targets(analysis)
    eyes = analysis_mod.observers(analysis)
    if not placed:
        report.add("error", "No luminaires: add at least one (Lighting > Luminaire, or "
                            "lighting.make_luminaire)")
    if not tgts and not eyes:
        report.add("error", "No targets: select faces or a floor/space and add a target "
                            "(Lighting > Target, or lighting.make_face_target / make_grid_target)")
    for lum in lums:
        report.extend(luminaire_mod.check(lum), lum.Name)
    for layout in layout_mod.layouts(analysis):
        report.extend(layout_mod.check(layout), layout.Name)
    for tgt in tgts:
        report.extend(target_mod.check(tgt), tgt.Name)
    for eye in eyes:
        report.extend(observer_mod.check(eye), eye.Name)
    for domain in analysis_mod.placement_domains(analysis):
        report.extend(domain_mod.check(domain), domain.Name)
    groups = analysis_mod.control_groups(analysis)
    for scene in light_scene_mod.scenes(analysis):
        report.extend(light_scene_mod.check(scene, groups), scene.Name)
    if exported is None:
        exported = collect.exported_objects(analysis.Document)
    # What the model leaves out and why (hidden objects stay in: visibility is a view choice).
    for obj, level, reason in collect.left_out(analysis.Document):
        report.add(level, f"'{obj.Label}' is left out of the lighting model: {reason}", obj.Name)
    hidden = [o.Label for o in exported if collect.is_hidden(o)]
    if hidden:
        shown = ", ".join(f"'{label}'" for label in hidden[:5])
        more = f" and {len(hidden) - 5} more" if len(hidden) > 5 else ""
        report.add("info", f"Hidden but in the lighting model: {shown}{more} (hiding is only a "
                           "view; use Exclude from lighting to leave an object out)")
    if not exported:
        report.add("warning", "No geometry: luminaires light the targets in free space")
    shapes = _check_geometry(report, exported)
    _check_luminaire_positions(report, placed, shapes)
    _check_coincident(report, placed)
    export = _check_scene_natively(report, analysis) if placed and tgts else None
    if need_solver:
        ok, reason = run.solver_available()
        if not ok:
            report.add("error", reason)
    return report, export
