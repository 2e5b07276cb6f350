"""Helpers shared by the workbench test suites (run inside freecadcmd)."""
import functools
import json
import math
import os
import tempfile
import unittest
from collections import Counter
from typing import Any, Dict, List, Tuple

import FreeCAD

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def solver_status() -> Tuple[bool, str]:
    """(available, reason) of the native module."""
    from lighting.solver import run

    return run.solver_available()


def needs_solver(test):
    """Skip a test when ``lightsolver`` cannot be imported — unless LIGHTSOLVER_REQUIRED=1
    (CMake sets it where it builds the module), where that is a failure."""
    @functools.wraps(test)
    def wrapper(self, *args, **kwargs):
        ok, reason = solver_status()
        if not ok:
            if os.environ.get("LIGHTSOLVER_REQUIRED") == "1":
                self.fail(f"lightsolver required but not importable: {reason}")
            self.skipTest(f"lightsolver module not importable: {reason}")
        return test(self, *args, **kwargs)
    return wrapper


def work_dir(name: str) -> str:
    """A fresh folder under the suite's work folder."""
    root = os.environ.get("LIGHTING_TEST_TMP") or tempfile.mkdtemp(prefix="lighting-test-")
    path = tempfile.mkdtemp(prefix=f"{name}-", dir=root)
    return path


def close_all() -> None:
    """Close every open document."""
    for name in list(FreeCAD.listDocuments()):
        FreeCAD.closeDocument(name)


def build_office(photons: int = 100000, seed: int = 1) -> Any:
    """The example office in a new document."""
    import office_model

    return office_model.build_office(photons=photons, seed=seed)


def load_scene(path: str) -> Dict[str, Any]:
    """A scene file with PLY meshes read back inline."""
    from lighting.export import ply

    with open(path, encoding="utf-8") as stream:
        scene = json.load(stream)
    for mesh in scene["meshes"]:
        if "file" in mesh:
            vertices, triangles = ply.read_ply(os.path.join(os.path.dirname(path), mesh["file"]))
            mesh["vertices"], mesh["triangles"] = vertices, triangles
    return scene


def mesh(scene: Dict[str, Any], name: str) -> Dict[str, Any]:
    """The mesh called ``name``."""
    for entry in scene["meshes"]:
        if entry["name"] == name:
            return entry
    raise KeyError(f"no mesh {name!r}; meshes: {[m['name'] for m in scene['meshes']]}")


def triangle_normals(entry: Dict[str, Any]) -> List[Tuple[Tuple[float, float, float], float]]:
    """(unit normal, area) of every triangle of a mesh (front = CCW winding)."""
    v = entry["vertices"]
    out = []
    for a, b, c in entry["triangles"]:
        u = [v[b][i] - v[a][i] for i in range(3)]
        w = [v[c][i] - v[a][i] for i in range(3)]
        n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
        length = math.sqrt(sum(x * x for x in n))
        out.append((tuple(x / length for x in n), 0.5 * length))
    return out


def open_edges(meshes: List[Dict[str, Any]]) -> int:
    """Edges used by one triangle only, over several meshes welded by position (mm)."""
    counter: Counter = Counter()
    for entry in meshes:
        keys = [tuple(round(x * 1000.0, 3) for x in p) for p in entry["vertices"]]
        for tri in entry["triangles"]:
            for i in range(3):
                a, b = keys[tri[i]], keys[tri[(i + 1) % 3]]
                counter[(min(a, b), max(a, b))] += 1
    return sum(1 for n in counter.values() if n == 1)


def triangle_keys(entry: Dict[str, Any]) -> List[frozenset]:
    """Each triangle as the set of its vertex positions (mm), to find doubled geometry."""
    keys = [tuple(round(x * 1000.0, 3) for x in p) for p in entry["vertices"]]
    return [frozenset(keys[i] for i in tri) for tri in entry["triangles"]]


class DocTestCase(unittest.TestCase):
    """Closes documents after each test."""

    def tearDown(self) -> None:
        close_all()
