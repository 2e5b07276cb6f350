# SPDX-License-Identifier: LGPL-2.1-or-later
"""What an analysis' exported scene depends on, as a fingerprint: are its results stale?

A run stores the fingerprint of the model it exported on its results object (solver/store.py);
comparing it with the model's fingerprint now says whether the results still describe the
model, and which inputs changed since. It is computed on demand, never by re-tessellating:

- ``settings``: the analysis' solver and export settings that change the numbers (photons,
  seed, confidence, bounces, accuracy, deflections, backend; not Threads, the display, the
  output folder);
- ``luminaire:<Name>``: every property of each luminaire the analysis uses (not its label,
  display or visibility), its global placement, its photometric file's size and date;
- ``target:<Name>``: each target's properties (not its requirements: pass/FAIL is judged
  against the current ones) and the signature of its shape (grid cells, faces);
- ``sky:<Name>``: each Sky's properties and the signature of its portals' shape;
- ``object:<Name>``: each exported object (export/collect.py: hidden ones included, excluded
  ones not): type, global placement, shape or mesh signature (counts, bounding box, area,
  volume) and material inputs (Reflectance/Transmittance, IFC type, its Arch material's data).

Placement domains and requirements do not change Em, so they are not part of it. Shape
signatures, the only costly part, are cached per object; an App document observer (installed
on first use, headless too) drops an object's entry whenever one of its properties changes,
so an unchanged model costs property reads only."""
from __future__ import annotations

import hashlib
import json
import os
from typing import Any, Dict, List, Optional, Tuple

import FreeCAD

from lighting.export import collect

#: Analysis properties that change the exported scene or the solver's numbers.
SETTINGS = ("Photons", "Seed", "Confidence", "MaxBounces", "TargetAccuracy", "MaxPhotons",
            "LinearDeflection", "AngularDeflection", "Backend", "Contributions")
#: Properties never part of a Lighting object's fingerprint.
SKIPPED_PROPERTIES = {"Label", "Label2", "Visibility", "ExpressionEngine", "Proxy", "Shape",
                      "AimDirection", "SpacingUsed", "CellsU", "CellsV"}
#: Property groups never part of a Lighting object's fingerprint.
SKIPPED_GROUPS = {"Display", "Requirements", "Results"}
#: Properties of geometry objects that decide their material (export/materials.py).
MATERIAL_PROPERTIES = ("Reflectance", "Transmittance", "IfcType", "IfcRole", "Role",
                       "WindowParts")

_shape_cache: Dict[Tuple[str, str], str] = {}
_observer: Optional["_CacheObserver"] = None


class _CacheObserver:
    """Drops cached shape signatures of objects that change (App observer, GUI or not)."""

    def slotChangedObject(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API)
        try:
            _shape_cache.pop((obj.Document.Name, obj.Name), None)
        except Exception:  # noqa: BLE001 - an object being deleted
            pass

    def slotDeletedObject(self, obj: Any) -> None:  # noqa: N802
        self.slotChangedObject(obj, "")

    def slotDeletedDocument(self, doc: Any) -> None:  # noqa: N802
        _forget_document(doc.Name)

    def slotCreatedDocument(self, doc: Any) -> None:  # noqa: N802
        _forget_document(doc.Name)


def _forget_document(name: str) -> None:
    for key in [k for k in _shape_cache if k[0] == name]:
        del _shape_cache[key]


def install() -> None:
    """Register the cache observer once."""
    global _observer
    if _observer is None:
        _observer = _CacheObserver()
        FreeCAD.addDocumentObserver(_observer)


# -- values ------------------------------------------------------------------------------
def _round(value: float) -> str:
    return f"{float(value):.9g}"


def _placement(placement: Any) -> List[str]:
    base, rot = placement.Base, placement.Rotation.Q
    return [_round(round(v, 6)) for v in (base.x, base.y, base.z)] + \
        [_round(round(q, 9)) for q in rot]


def _box(box: Any) -> List[str]:
    if not box.isValid():
        return []
    return [_round(round(v, 4)) for v in (box.XMin, box.YMin, box.ZMin,
                                          box.XMax, box.YMax, box.ZMax)]


def shape_signature(shape: Any) -> List[Any]:
    """Counts, bounding box, area, volume and vertex sum of a shape (no tessellation)."""
    if shape is None or shape.isNull():
        return ["null"]
    total = FreeCAD.Vector()
    for vertex in shape.Vertexes:
        total += vertex.Point
    try:
        volume = shape.Volume
    except Exception:  # noqa: BLE001 - compounds of odd things
        volume = 0.0
    return [shape.ShapeType, len(shape.Solids), len(shape.Faces), len(shape.Edges),
            len(shape.Vertexes), _box(shape.BoundBox), _round(shape.Area), _round(volume),
            [_round(round(v, 3)) for v in (total.x, total.y, total.z)]]


def mesh_signature(mesh: Any) -> List[Any]:
    """Counts, bounding box, area and volume of a mesh."""
    return ["mesh", mesh.CountPoints, mesh.CountFacets, _box(mesh.BoundBox),
            _round(mesh.Area), _round(mesh.Volume)]


def _cached_signature(obj: Any) -> str:
    key = (obj.Document.Name, obj.Name)
    found = _shape_cache.get(key) if _observer is not None else None
    if found is None:
        if collect.is_mesh(obj):
            sig = mesh_signature(obj.Mesh)
        else:
            sig = shape_signature(getattr(obj, "Shape", None))
        found = json.dumps(sig)
        if _observer is not None:
            _shape_cache[key] = found
    return found


def value_of(value: Any) -> Any:
    """A JSON-able, stable form of a property value."""
    if value is None or isinstance(value, (bool, int, str)):
        return value
    if isinstance(value, float):
        return _round(value)
    if hasattr(value, "TypeId") and hasattr(value, "Name"):
        return f"<{value.Name}>"
    if isinstance(value, FreeCAD.Placement):
        return _placement(value)
    if isinstance(value, FreeCAD.Vector):
        return [_round(round(v, 9)) for v in (value.x, value.y, value.z)]
    if hasattr(value, "Value") and hasattr(value, "Unit"):  # Quantity
        return _round(value.Value)
    if isinstance(value, (list, tuple)):
        return [value_of(v) for v in value]
    if isinstance(value, dict):
        return {str(k): value_of(v) for k, v in sorted(value.items())}
    return repr(value)


def _properties(obj: Any, names: Optional[Tuple[str, ...]] = None) -> Dict[str, Any]:
    out: Dict[str, Any] = {}
    for name in names or obj.PropertiesList:
        if name not in obj.PropertiesList or name in SKIPPED_PROPERTIES:
            continue
        if names is None and obj.getGroupOfProperty(name) in SKIPPED_GROUPS:
            continue
        out[name] = value_of(getattr(obj, name))
    return out


def _digest(data: Any) -> str:
    text = json.dumps(data, sort_keys=True, separators=(",", ":"))
    return hashlib.sha1(text.encode("utf-8")).hexdigest()[:16]


def _file_facts(path: str) -> List[Any]:
    try:
        stat = os.stat(path)
    except OSError:
        return [path, "missing"]
    return [path, stat.st_size, int(stat.st_mtime)]


# -- entries -----------------------------------------------------------------------------
def _material(obj: Any, depth: int = 0) -> Dict[str, Any]:
    """Everything the material resolver reads from an object or an Arch (multi-)material."""
    data = _properties(obj, MATERIAL_PROPERTIES + ("Material", "Materials", "Names"))
    for key in ("Material", "Materials"):
        linked = getattr(obj, key, None) if key in obj.PropertiesList else None
        targets = linked if isinstance(linked, (list, tuple)) else [linked]
        for item in targets:
            if depth < 3 and hasattr(item, "TypeId") and hasattr(item, "Name"):
                data[f"{key}:{item.Name}"] = _material(item, depth + 1)
    return data


def _geometry_entry(obj: Any) -> str:
    from lighting.geometry import global_placement

    return _digest([obj.TypeId, _placement(global_placement(obj)), _cached_signature(obj),
                    _material(obj)])


def local_entry(obj: Any) -> str:
    """An exported object's entry without its placement: type, the signature of its shape or
    mesh in its own coordinates, material inputs. Equal before and after an edit when the edit
    only moved the object (solver/live.py then moves its instance instead of exporting)."""
    from lighting.geometry import global_placement, global_shape

    if collect.is_mesh(obj):
        mesh = obj.Mesh.copy()
        mesh.Placement = FreeCAD.Placement()
        signature = mesh_signature(mesh)
    else:
        shape = global_shape(obj)
        shape.Placement = global_placement(obj).inverse().multiply(shape.Placement)
        signature = shape_signature(shape)
    return _digest([obj.TypeId, signature, _material(obj)])


def _luminaire_entry(lum: Any) -> str:
    from lighting.geometry import global_placement

    data = _properties(lum)
    data["global_placement"] = _placement(global_placement(lum))
    path = str(getattr(lum, "PhotometricFile", "") or "")
    if path:
        data["file"] = _file_facts(path)
    return _digest(data)


def _target_entry(tgt: Any) -> str:
    return _digest([_properties(tgt), _cached_signature(tgt)])


def of_analysis(analysis: Any) -> Dict[str, str]:
    """The fingerprint of what the analysis would export now: key -> short digest."""
    from lighting.objects import analysis as analysis_mod

    install()
    result = {"settings": _digest(_properties(analysis, SETTINGS))}
    for lum in analysis_mod.luminaires(analysis):
        result[f"luminaire:{lum.Name}"] = _luminaire_entry(lum)
    for tgt in analysis_mod.targets(analysis):
        result[f"target:{tgt.Name}"] = _target_entry(tgt)
    for eye in analysis_mod.observers(analysis):
        result[f"observer:{eye.Name}"] = _digest([_properties(eye),
                                                  str(eye.getGlobalPlacement())])
    from lighting.export import daylight

    for sky in daylight.skies(analysis):  # its settings and its portals (its drawn shape)
        result[f"sky:{sky.Name}"] = _digest([_properties(sky), _geometry_entry(sky)])
    for obj in collect.exported_objects(analysis.Document):
        result[f"object:{obj.Name}"] = _geometry_entry(obj)
    return result


def dumps(fingerprint: Dict[str, str]) -> str:
    """Compact JSON text of a fingerprint (stored on the results object)."""
    return json.dumps(fingerprint, sort_keys=True, separators=(",", ":"))


def loads(text: str) -> Optional[Dict[str, str]]:
    """A stored fingerprint, or None when there is none (results of older versions)."""
    if not text:
        return None
    try:
        data = json.loads(text)
    except ValueError:
        return None
    return data if isinstance(data, dict) else None


def differences(stored: Dict[str, str], current: Dict[str, str], doc: Any) -> List[str]:
    """What changed, for people: "luminaire 'Luminaire01' changed", "'Ceiling' left out"..."""
    words = {"luminaire": "luminaire", "target": "target", "object": ""}
    out: List[str] = []
    for key in sorted(set(stored) | set(current)):
        if stored.get(key) == current.get(key):
            continue
        if key == "settings":
            out.append("analysis settings changed")
            continue
        kind, _, name = key.partition(":")
        obj = doc.getObject(name) if doc is not None else None
        label = obj.Label if obj is not None else name
        what = f"{words.get(kind, kind)} '{label}'".strip()
        if key not in current:
            out.append(f"{what} removed" if obj is None or kind != "object"
                       else f"{what} left out")
        elif key not in stored:
            out.append(f"{what} added")
        else:
            out.append(f"{what} changed")
    return out
