#!/usr/bin/python3
"""Writes the optimization examples modelled after Avas & Fernandez, Sec. V:

* cornell/    a Cornell box with a faceted glass lens (a caustic) and a faceted mirror sphere,
              a vertical directional light, and a cone moved on the floor to maximise its
              irradiance: the optimum is under the lens centre (0.65, 0.45).
* conference/ a meeting room (table, chairs, podium: tens of thousands of triangles) with two
              square ceiling lights moved in x, y to maximise the irradiance of the podium's desk: the
              optimum has one light above the podium (2.0, 6.0) and the other next to it (two
              lights never share a cell; the paper's search put both in one).
* hangar/     a hangar, mirror-symmetric about x = 20, with two tube lights (x = 9.5 and 30.5) and
              a glass box moved on the floor: two optima, one under each light.
* small_room/ a 4 x 4 m room, two ceiling points and their common flux: minimise installed
              flux subject to Em >= 300 lx and U0 >= 0.6 on the workplane.

Search settings in the files are the benchmark's (docs/BENCHMARKS.md); the tests shrink grids,
iterations and photons. Run: /usr/bin/python3 Examples/optimization/generate.py
"""
from __future__ import annotations

import json
import math
from pathlib import Path

from geometry import (Mesh, biconvex_lens, box, cone, cylinder, grid_quad, sphere,
                      write_ply)

HERE = Path(__file__).resolve().parent
FORMAT = "lightsolver.scene/1"


def room(x: float, y: float, z: float, n: int = 1) -> dict[str, Mesh]:
    """Floor, ceiling and walls of a box room facing inward, each split n x n."""
    return {
        "floor": grid_quad((0, 0, 0), (x, 0, 0), (0, y, 0), n, n),
        "ceiling": grid_quad((0, 0, z), (0, y, 0), (x, 0, 0), n, n),
        "walls": grid_quad((0, 0, 0), (0, 0, z), (x, 0, 0), n, n)
        .add(grid_quad((0, y, 0), (x, 0, 0), (0, 0, z), n, n))
        .add(grid_quad((0, 0, 0), (0, y, 0), (0, 0, z), n, n))
        .add(grid_quad((x, 0, 0), (0, 0, z), (0, y, 0), n, n)),
    }


def write_scene(folder: str, scene: dict, meshes: dict[str, tuple[Mesh, str]]) -> None:
    """Writes <folder>/<name>.ply for every mesh and <folder>/<folder>.json."""
    out = HERE / folder
    out.mkdir(exist_ok=True)
    scene["meshes"] = []
    for name, (mesh, material) in meshes.items():
        entry = {"name": name, "material": material}
        if len(mesh.triangles) <= 200:  # small meshes inline (Assimp rejects some tiny PLYs)
            entry["vertices"] = [[round(c, 6) for c in v] for v in mesh.vertices]
            entry["triangles"] = [list(t) for t in mesh.triangles]
        else:
            write_ply(out / f"{name}.ply", mesh)
            entry["file"] = f"{name}.ply"
        scene["meshes"].append(entry)
    (out / f"{folder}.json").write_text(json.dumps(scene) + "\n")
    tris = sum(len(m.triangles) for m, _ in meshes.values())
    print(f"{folder}: {tris} triangles")


def cornell() -> None:
    """1 m Cornell box, light straight down, lens focusing onto the floor zone of the cone."""
    walls = room(1, 1, 1, 4)
    red = grid_quad((0, 0, 0), (0, 1, 0), (0, 0, 1), 4, 4)
    green = grid_quad((1, 0, 0), (0, 0, 1), (0, 1, 0), 4, 4)
    back = grid_quad((0, 1, 0), (1, 0, 0), (0, 0, 1), 4, 4).add(
        grid_quad((0, 0, 0), (0, 0, 1), (1, 0, 0), 4, 4))
    white = walls["floor"].add(walls["ceiling"]).add(back)
    meshes = {
        "white": (white, "white"), "red": (red, "red"), "green": (green, "green"),
        # f = R / (2 (n - 1)) = 0.48 m for R = 0.5, n = 1.52: the focus lies ~0.12 m above
        # the floor, inside the cone's height.
        "lens": (biconvex_lens((0.65, 0.45, 0.6), 0.15, 0.5, 96, 24), "glass"),
        "sphere": (sphere((0.22, 0.75, 0.55), 0.14, 128, 64), "mirror"),
        # Built at the origin: the translation variable places this point on the floor.
        "cone": (cone((0, 0, 0), 0.06, 0.15, 128, 24), "grey"),
    }
    scene = {
        "format": FORMAT,
        "materials": {
            "white": {"type": "diffuse", "reflectance": 0.7},
            "red": {"type": "diffuse", "reflectance": 0.5},
            "green": {"type": "diffuse", "reflectance": 0.5},
            "grey": {"type": "diffuse", "reflectance": 0.5},
            "glass": {"type": "glass", "ior": 1.52},
            "mirror": {"type": "mirror", "reflectance": 0.95},
        },
        "luminaires": [{"name": "sun", "type": "directional", "direction": [0, 0, -1],
                        "corner": [0.005, 0.005, 0.995], "edge1": [0.99, 0, 0],
                        "edge2": [0, 0.99, 0], "illuminance_lx": 1000}],
        "targets": [{"name": "cone", "type": "surface", "mesh": "cone"}],
        "optimization": {
            "intention": {"type": "maximize_mean_illuminance", "target": "cone"},
            "variables": [{"type": "translation", "mesh": "cone", "corner": [0.1, 0.1, 0],
                           "edge1": [0.8, 0, 0], "edge2": [0, 0.8, 0], "cells": [24, 24]}],
            "search": {"seed": 1, "screening_photons": 12544, "confirmation_photons": 2660000,
                       "strategy": "refine_at_end", "max_iterations": 1000,
                       "initial": [[0, 0]]},
        },
    }
    write_scene("cornell", scene, meshes)


def chair(x: float, y: float, facing: float) -> Mesh:
    """Seat, back and four round legs (~1900 triangles)."""
    m = box(-0.22, -0.22, 0.43, 0.22, 0.22, 0.47)
    m.add(box(-0.22, 0.18, 0.47, 0.22, 0.22, 0.9))
    for lx in (-0.19, 0.19):
        for ly in (-0.19, 0.19):
            m.add(cylinder((lx, ly, 0.0), 0.02, 0.43, 48, 9))
    c, s = math.cos(facing), math.sin(facing)
    return Mesh([(x + c * vx - s * vy, y + s * vx + c * vy, vz) for vx, vy, vz in m.vertices],
                m.triangles)


def conference() -> None:
    """12 x 8 x 3 m room, blackboard on x = 0, podium near it, table with 16 chairs."""
    walls = room(12, 8, 3, 8)
    table = box(3.5, 3.2, 0.72, 9.5, 4.8, 0.76)
    for lx in (3.7, 9.3):
        for ly in (3.4, 4.6):
            table.add(cylinder((lx, ly, 0), 0.04, 0.72, 64, 12))
    chairs = Mesh()
    for i in range(7):
        chairs.add(chair(4.0 + i * 0.85, 2.7, 0.0))
        chairs.add(chair(4.0 + i * 0.85, 5.3, math.pi))
    chairs.add(chair(3.0, 4.0, -math.pi / 2)).add(chair(10.0, 4.0, math.pi / 2))
    meshes = {
        "room": (walls["floor"].add(walls["walls"]), "wall"),
        "ceiling": (walls["ceiling"], "ceiling"),
        "blackboard": (grid_quad((0.01, 3.5, 0.9), (0, 3, 0), (0, 0, 1.2), 1, 1), "board"),
        "table": (table, "wood"), "chairs": (chairs, "fabric"),
        "podium": (box(1.7, 5.75, 0.0, 2.3, 6.25, 1.1, bottom=False, top=False), "wood"),
        # The reading desk, the target: its own mesh so that only it is measured.
        "desk": (grid_quad((1.7, 5.75, 1.1), (0.6, 0, 0), (0, 0.5, 0), 1, 1), "wood"),
    }
    lights = [{"name": f"light{i}", "type": "area", "flux_lm": 3000,
               "corner": [11.0 - 0.2, 0.6 + 0.5 * i - 0.2, 2.98], "edge1": [0, 0.4, 0],
               "edge2": [0.4, 0, 0]} for i in range(2)]  # facing down: edge1 x edge2 = -z
    ceiling_rect = {"corner": [0.5, 0.5, 2.98], "edge1": [11, 0, 0], "edge2": [0, 7, 0],
                    "cells": [33, 21]}
    scene = {
        "format": FORMAT,
        "materials": {"wall": {"type": "diffuse", "reflectance": 0.5},
                      "ceiling": {"type": "diffuse", "reflectance": 0.8},
                      "board": {"type": "diffuse", "reflectance": 0.1},
                      "wood": {"type": "diffuse", "reflectance": 0.4},
                      "fabric": {"type": "diffuse", "reflectance": 0.3}},
        "luminaires": lights,
        "targets": [{"name": "podium", "type": "surface", "mesh": "desk"}],
        "optimization": {
            "intention": {"type": "maximize_mean_illuminance", "target": "podium"},
            "variables": [dict(type="position", luminaire="light0", **ceiling_rect),
                          dict(type="position", luminaire="light1", **ceiling_rect)],
            "search": {"seed": 1, "screening_photons": 9216, "confirmation_photons": 2660000,
                       "strategy": "confirm", "max_iterations": 1000,
                       "initial": [[32, 0, 32, 1]]},
        },
    }
    write_scene("conference", scene, meshes)


def hangar() -> None:
    """40 x 20 x 10 m hangar, roof trusses, two 6 m tube lights, a 1.5 m glass box."""
    walls = room(40, 20, 10, 10)
    trusses = Mesh()
    for i in range(9):
        x = 2.0 + i * 4.5  # symmetric about x = 20
        for j in range(8):
            trusses.add(cylinder((x, 1.25 + j * 2.5, 8.0), 0.08, 1.6, 40, 6))
    lights = [{"name": f"tube{i}", "type": "area", "flux_lm": 20000,
               "corner": [x - 3.0, 9.85, 9.9], "edge1": [0, 0.3, 0], "edge2": [6.0, 0, 0]}
              for i, x in enumerate((9.5, 30.5))]
    scene = {
        "format": FORMAT,
        "materials": {"concrete": {"type": "diffuse", "reflectance": 0.4},
                      "steel": {"type": "glossy", "reflectance": 0.2, "specular": 0.4,
                                "roughness": 0.3},
                      "glass": {"type": "glass", "ior": 1.5}},
        "luminaires": lights,
        "targets": [{"name": "box", "type": "surface", "mesh": "box"}],
        "optimization": {
            "intention": {"type": "maximize_mean_illuminance", "target": "box"},
            "variables": [{"type": "translation", "mesh": "box", "corner": [2, 2, 0],
                           "edge1": [36, 0, 0], "edge2": [0, 16, 0], "cells": [36, 15]}],
            "search": {"seed": 1, "confidence": 0.99, "screening_photons": 30976,
                       "confirmation_photons": 2660000, "strategy": "refine_at_end",
                       "max_iterations": 1000, "initial": [[17, 0]]},
        },
    }
    meshes = {"hall": (walls["floor"].add(walls["walls"]).add(walls["ceiling"]), "concrete"),
              "trusses": (trusses, "steel"),
              # Closed (a glass body) and lifted 1 cm so its base does not coincide with the floor.
              "box": (box(-0.75, -0.75, 0.01, 0.75, 0.75, 1.51), "glass")}
    write_scene("hangar", scene, meshes)


def small_room() -> None:
    """4 x 4 x 2.8 m room, workplane grid 3 x 3 m at 0.8 m, two ceiling points, one flux."""
    walls = room(4, 4, 2.8)
    ceiling_rect = {"corner": [0.5, 0.5, 2.7], "edge1": [3, 0, 0], "edge2": [0, 3, 0],
                    "cells": [3, 3]}
    scene = {
        "format": FORMAT,
        "materials": {"wall": {"type": "diffuse", "reflectance": 0.5},
                      "floor": {"type": "diffuse", "reflectance": 0.2},
                      "ceiling": {"type": "diffuse", "reflectance": 0.7}},
        "luminaires": [{"name": "a", "type": "point", "flux_lm": 1000, "position": [0.5, 0.5, 2.7]},
                       {"name": "b", "type": "point", "flux_lm": 1000, "position": [3.5, 0.5, 2.7]}],
        "targets": [{"name": "workplane", "type": "grid", "corner": [0.5, 0.5, 0.8],
                     "edge1": [3, 0, 0], "edge2": [0, 3, 0], "cells": [3, 3]}],
        "optimization": {
            "intention": {"type": "minimize_installed_flux", "target": "workplane",
                          "min_mean_lux": 300, "min_uniformity": 0.6},
            "variables": [dict(type="position", luminaire="a", **ceiling_rect),
                          dict(type="position", luminaire="b", **ceiling_rect),
                          {"type": "flux", "luminaires": ["a", "b"],
                           "levels_lm": [1000, 1500, 2000, 2500, 3000, 3500, 4000, 5000]}],
            "search": {"seed": 1, "screening_photons": 16384, "confirmation_photons": 262144,
                       "strategy": "confirm", "max_iterations": 30},
        },
    }
    write_scene("small_room", scene, {"floor": (walls["floor"], "floor"),
                                      "walls": (walls["walls"], "wall"),
                                      "ceiling": (walls["ceiling"], "ceiling")})


if __name__ == "__main__":
    cornell()
    conference()
    hangar()
    small_room()
