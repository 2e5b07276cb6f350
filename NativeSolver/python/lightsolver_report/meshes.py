# SPDX-License-Identifier: LGPL-2.1-or-later
"""The scene's geometry for the report's pictures: every mesh as numpy arrays (inline
vertices, or a PLY / OBJ file beside the scene), its ``transform`` applied, zero-area and
non-finite triangles left out, with its material's kind and reflectance.

The solver reads mesh files with Assimp; the report only draws them, so a small numpy reader
of the two formats the scene format names does (PLY ascii and binary, polygons fanned into
triangles; OBJ ``v`` and ``f`` lines). A file it cannot read is left out of the pictures and
said in ``notes``; the calculation itself is not affected."""
from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

#: Reflectance used for the grey shade of each material type when the scene gives none
#: (docs/scene-format.md, "Materials").
DEFAULT_REFLECTANCE = {"diffuse": 0.5, "mirror": 0.9, "glossy": 0.5, "glass": 0.1}

#: PLY scalar types as numpy type codes.
_PLY_TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2",
              "int16": "i2", "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4",
              "uint": "u4", "uint32": "u4", "float": "f4", "float32": "f4", "double": "f8",
              "float64": "f8"}


class MeshFileError(ValueError):
    """A mesh file the report's reader cannot read (the message says why)."""


@dataclass
class Mesh:
    """One scene mesh in world coordinates (metres)."""

    name: str
    label: str
    material: str
    kind: str  # the material's type: diffuse, mirror, glossy, glass
    reflectance: float  # for the grey shade: reflectance (+ specular for glossy)
    vertices: np.ndarray  # (n, 3) float64
    triangles: np.ndarray  # (m, 3) int64, each of non-zero area

    @property
    def corners(self) -> np.ndarray:
        """The triangles' corners, shape (m, 3, 3)."""
        return self.vertices[self.triangles]


# --- file readers ---------------------------------------------------------------------------

def _fan(polygons: List[List[int]]) -> np.ndarray:
    """Triangles of polygons given as vertex index lists (fan from the first corner)."""
    tris = [(p[0], p[i], p[i + 1]) for p in polygons for i in range(1, len(p) - 1)]
    return np.asarray(tris, dtype=np.int64).reshape(-1, 3)


def _ply_header(data: bytes) -> Tuple[str, List[Tuple[str, int, List[Tuple[str, ...]]]], int]:
    """The PLY format, its elements (name, count, properties) and where the body starts."""
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise MeshFileError("not a PLY file (no 'ply' ... 'end_header' header)")
    body = data.index(b"\n", end) + 1
    fmt, elements = "", []
    for line in data[:end].decode("ascii", "replace").splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == "format":
            fmt = words[1]
        elif words[0] == "element":
            elements.append((words[1], int(words[2]), []))
        elif words[0] == "property" and elements:
            elements[-1][2].append(tuple(words[1:]))
    if fmt not in ("ascii", "binary_little_endian", "binary_big_endian"):
        raise MeshFileError(f"unknown PLY format '{fmt}'")
    return fmt, elements, body


def _ply_ascii(text: List[str], elements) -> Dict[str, Any]:
    out: Dict[str, Any] = {}
    pos = 0
    for name, count, props in elements:
        rows = []
        for _ in range(count):
            row = []
            for prop in props:
                if prop[0] == "list":
                    n = int(float(text[pos]))
                    row.append([int(float(t)) for t in text[pos + 1:pos + 1 + n]])
                    pos += 1 + n
                else:
                    row.append(float(text[pos]))
                    pos += 1
            rows.append(row)
        out[name] = rows
    return out


def _fixed_lists(data: bytes, offset: int, count: int, props, endian: str):
    """An element of one list property whose rows all have the first row's length (the usual
    triangle faces), read at once: ([[indices]] rows, the offset after it); else None."""
    if len(props) != 1 or props[0][0] != "list" or count == 0:
        return None
    ctype = np.dtype(endian + _PLY_TYPES[props[0][1]])
    itype = np.dtype(endian + _PLY_TYPES[props[0][2]])
    n = int(np.frombuffer(data, ctype, 1, offset)[0])
    dtype = np.dtype([("n", ctype), ("i", itype, (n,))])
    if n < 3 or offset + dtype.itemsize * count > len(data):
        return None
    rows = np.frombuffer(data, dtype=dtype, count=count, offset=offset)
    if np.any(rows["n"] != n):
        return None
    return rows["i"].astype(np.int64), offset + dtype.itemsize * count


def _ply_binary(data: bytes, offset: int, elements, endian: str) -> Dict[str, Any]:
    out: Dict[str, Any] = {}
    for name, count, props in elements:
        if all(p[0] != "list" for p in props):  # fixed-size rows: one numpy read
            dtype = np.dtype([(p[1], endian + _PLY_TYPES[p[0]]) for p in props])
            rows = np.frombuffer(data, dtype=dtype, count=count, offset=offset)
            out[name] = [[float(r[p[1]]) for p in props] for r in rows] if name != "vertex" \
                else rows
            offset += dtype.itemsize * count
            continue
        fixed = _fixed_lists(data, offset, count, props, endian)
        if fixed is not None:  # every face has the same corner count: one numpy read
            out[name], offset = fixed
            continue
        rows = []
        for _ in range(count):
            row = []
            for prop in props:
                if prop[0] == "list":
                    ctype = np.dtype(endian + _PLY_TYPES[prop[1]])
                    itype = np.dtype(endian + _PLY_TYPES[prop[2]])
                    n = int(np.frombuffer(data, ctype, 1, offset)[0])
                    offset += ctype.itemsize
                    row.append(np.frombuffer(data, itype, n, offset).astype(np.int64).tolist())
                    offset += itype.itemsize * n
                else:
                    ctype = np.dtype(endian + _PLY_TYPES[prop[0]])
                    row.append(float(np.frombuffer(data, ctype, 1, offset)[0]))
                    offset += ctype.itemsize
            rows.append(row)
        out[name] = rows
    return out


def read_ply(path: str) -> Tuple[np.ndarray, np.ndarray]:
    """Vertices (n, 3) and triangles (m, 3) of a PLY file (ascii or binary)."""
    with open(path, "rb") as handle:
        data = handle.read()
    fmt, elements, body = _ply_header(data)
    try:
        if fmt == "ascii":
            parsed = _ply_ascii(data[body:].decode("ascii", "replace").split(), elements)
        else:
            endian = "<" if fmt == "binary_little_endian" else ">"
            parsed = _ply_binary(data, body, elements, endian)
    except (IndexError, ValueError, KeyError) as exc:
        raise MeshFileError(f"truncated or malformed PLY body ({exc})") from exc
    props = {name: props for name, _, props in elements}
    if "vertex" not in parsed:
        raise MeshFileError("no vertex element")
    names = [p[-1] for p in props["vertex"]]
    rows = parsed["vertex"]
    if isinstance(rows, np.ndarray):
        vertices = np.stack([rows[a].astype(np.float64) for a in "xyz"], axis=1) \
            if len(rows) else np.zeros((0, 3))
    else:
        idx = [names.index(a) for a in "xyz"]
        vertices = np.asarray([[r[i] for i in idx] for r in rows], dtype=np.float64)
    faces = parsed.get("face", [])
    if isinstance(faces, np.ndarray):  # (k, n) corner indices: fan each row at once
        fan = [faces[:, [0, i, i + 1]] for i in range(1, faces.shape[1] - 1)]
        return vertices.reshape(-1, 3), np.stack(fan, axis=1).reshape(-1, 3)
    return vertices.reshape(-1, 3), _fan([v for row in faces for v in row
                                          if isinstance(v, list)])


def read_obj(path: str) -> Tuple[np.ndarray, np.ndarray]:
    """Vertices and triangles of an OBJ file (``v`` and ``f`` lines; negative indices count
    from the end)."""
    vertices: List[List[float]] = []
    faces: List[List[int]] = []
    with open(path, encoding="utf-8", errors="replace") as handle:
        for line in handle:
            words = line.split()
            if not words:
                continue
            if words[0] == "v" and len(words) >= 4:
                vertices.append([float(w) for w in words[1:4]])
            elif words[0] == "f" and len(words) >= 4:
                idx = [int(w.split("/")[0]) for w in words[1:]]
                faces.append([i - 1 if i > 0 else len(vertices) + i for i in idx])
    return np.asarray(vertices, dtype=np.float64).reshape(-1, 3), _fan(faces)


def read_mesh_file(path: str) -> Tuple[np.ndarray, np.ndarray]:
    """A PLY or OBJ file's vertices and triangles; MeshFileError when it cannot be read."""
    try:
        if path.lower().endswith(".obj"):
            return read_obj(path)
        return read_ply(path)
    except OSError as exc:
        raise MeshFileError(str(exc)) from exc
    except ValueError as exc:
        raise MeshFileError(str(exc)) from exc


# --- scene meshes -----------------------------------------------------------------------------

def clean(vertices: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """The triangles with valid indices, finite corners and a non-zero area."""
    vertices = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    if not len(triangles):
        return triangles
    ok = np.all((triangles >= 0) & (triangles < len(vertices)), axis=1)
    triangles = triangles[ok]
    corners = vertices[triangles]
    ok = np.all(np.isfinite(corners), axis=(1, 2))
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    size = np.max(np.abs(corners), axis=(1, 2)) + 1.0
    ok &= np.linalg.norm(cross, axis=1) > 1e-12 * size * size
    return triangles[ok]


def _transformed(vertices: np.ndarray, transform: Any) -> np.ndarray:
    try:
        matrix = np.asarray(transform, dtype=np.float64).reshape(4, 4)
    except (TypeError, ValueError):
        return vertices
    return vertices @ matrix[:3, :3].T + matrix[:3, 3]


def material_shade(material: Dict[str, Any]) -> Tuple[str, float]:
    """A material's type and the reflectance its grey shade stands for."""
    kind = str(material.get("type", "diffuse"))
    value = material.get("reflectance", DEFAULT_REFLECTANCE.get(kind, 0.5))
    try:
        reflectance = float(value)
        if kind == "glossy":
            reflectance += float(material.get("specular", 0.5))
    except (TypeError, ValueError):
        reflectance = 0.5
    return kind, float(min(1.0, max(0.0, reflectance))) if np.isfinite(reflectance) else 0.5


def load_meshes(scene: Dict[str, Any], base_dir: str,
                labels: Optional[Dict[str, str]] = None) -> Tuple[List[Mesh], List[str]]:
    """Every mesh of the scene, in scene order, and notes on meshes that could not be read."""
    labels = labels or {}
    materials = scene.get("materials") if isinstance(scene.get("materials"), dict) else {}
    meshes: List[Mesh] = []
    notes: List[str] = []
    for entry in scene.get("meshes", []) or []:
        if not isinstance(entry, dict):
            continue
        name = str(entry.get("name", ""))
        label = str(labels.get(name, labels.get(name.split(".")[0], name)))
        try:
            if entry.get("file"):
                vertices, triangles = read_mesh_file(os.path.join(base_dir, str(entry["file"])))
            else:
                vertices = np.asarray(entry.get("vertices", []), dtype=np.float64).reshape(-1, 3)
                triangles = np.asarray(entry.get("triangles", []), dtype=np.int64).reshape(-1, 3)
        except (MeshFileError, TypeError, ValueError):
            # said without the file's name or path: the page is for the client
            notes.append(f"“{label}” is not drawn: its geometry could not be read")
            continue
        if entry.get("transform") is not None:
            vertices = _transformed(vertices, entry["transform"])
        triangles = clean(vertices, triangles)
        material = materials.get(entry.get("material"), {})
        kind, reflectance = material_shade(material if isinstance(material, dict) else {})
        meshes.append(Mesh(name, label, str(entry.get("material", "")), kind, reflectance,
                           vertices, triangles))
    return meshes, notes
