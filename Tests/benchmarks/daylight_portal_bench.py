# SPDX-License-Identifier: LGPL-2.1-or-later
"""Portal vs no portal (docs/BENCHMARKS.md, "Sky: portal vs the site's disc"): the time and the
photons a side-lit room's floor grid needs until its worst cell is within +-2 % (`lightsolver
run --accuracy 0.02 --per-cell`), the sky entering through the window's portal, and from the
disc covering the site (no portal), with and without a black overhang and neighbour outside.
One run; prints a Markdown table.

    /usr/bin/python3 Tests/benchmarks/daylight_portal_bench.py build/NativeSolver/cli/lightsolver
"""
import json
import os
import subprocess
import sys
import tempfile
from typing import Dict, List, Tuple

Vec = Tuple[float, float, float]


def quad(corner: Vec, e1: Vec, e2: Vec) -> Tuple[List[Vec], List[Tuple[int, int, int]]]:
    """The parallelogram corner + s e1 + t e2 as two triangles (front e1 x e2)."""
    c = corner
    p = [c, tuple(c[i] + e1[i] for i in range(3)),
         tuple(c[i] + e1[i] + e2[i] for i in range(3)), tuple(c[i] + e2[i] for i in range(3))]
    return p, [(0, 1, 2), (0, 2, 3)]


def mesh(name: str, material: str, quads: List[Tuple[Vec, Vec, Vec]]) -> Dict:
    """A mesh of quads."""
    vertices: List[Vec] = []
    triangles: List[Tuple[int, int, int]] = []
    for q in quads:
        p, t = quad(*q)
        base = len(vertices)
        vertices += p
        triangles += [(a + base, b + base, c + base) for a, b, c in t]
    return {"name": name, "material": material, "vertices": vertices, "triangles": triangles}


def room() -> Dict:
    """A 3 x 3 x 2.5 m room facing in, a 1.5 x 1.2 m window (x 0.75-2.25, z 0.8-2.0) in y = 0."""
    X, Y, Z = (3, 0, 0), (0, 3, 0), (0, 0, 2.5)
    quads = [((0, 0, 0), X, Y), ((0, 0, 2.5), Y, X), ((0, 3, 0), X, Z), ((0, 0, 0), Y, Z),
             ((3, 0, 0), Z, Y)]
    # The wall y = 0 (front +y) around the window.
    quads += [((0, 0, 0), (0, 0, 0.8), (3, 0, 0)), ((0, 0, 2.0), (0, 0, 0.5), (3, 0, 0)),
              ((0, 0, 0.8), (0, 0, 1.2), (0.75, 0, 0)), ((2.25, 0, 0.8), (0, 0, 1.2), (0.75, 0, 0))]
    return mesh("room", "grey", quads)


def scene(portal: bool, obstructed: bool) -> Dict:
    """The side-lit room under a CIE clear sky (type 12) with ground, a 5 x 5 floor grid."""
    sky = {"name": "sky", "type": "sky", "model": "cie", "cie_type": 12,
           "sun_direction": [0.2, -0.7, 0.6], "zenith_luminance_cd_m2": 5000,
           "ground_reflectance": 0.2}
    if portal:
        sky["portals"] = [{"corner": [0.75, 0, 0.8], "edge1": [0, 0, 1.2], "edge2": [1.5, 0, 0]}]
    else:
        sky["site"] = {"centre": [1.5, 0.5, 1.25], "radius_m": 3.6}
    meshes = [room()]
    if obstructed:
        meshes.append(mesh("overhang", "black", [((0, -0.8, 2.1), (3, 0, 0), (0, 0.8, 0))]))
        meshes.append(mesh("neighbour", "black", [((-1, -1.5, 0), (5, 0, 0), (0, 0, 2.2))]))
    return {"format": "lightsolver.scene/1",
            "materials": {"grey": {"type": "diffuse", "reflectance": 0.5},
                          "black": {"type": "diffuse", "reflectance": 0.0}},
            "meshes": meshes, "luminaires": [sky],
            "targets": [{"name": "floor", "type": "grid", "corner": [0.25, 0.25, 0.8],
                         "edge1": [2.5, 0, 0], "edge2": [0, 2.5, 0], "cells": [5, 5]}],
            "settings": {"seed": 7}}


def run(cli: str, folder: str, portal: bool, obstructed: bool) -> Tuple[int, float, float]:
    """(photons, tracing seconds, grid mean lx) until every cell is within +-2 %."""
    name = ("portal" if portal else "disc") + ("_obstructed" if obstructed else "")
    path = os.path.join(folder, name + ".json")
    out = os.path.join(folder, name + ".results.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(scene(portal, obstructed), f)
    subprocess.run([cli, "run", path, "--accuracy", "0.02", "--per-cell", "--backend", "embree",
                    "--max-seconds", "600", "--out", out], check=True,
                   stdout=subprocess.DEVNULL)
    with open(out, encoding="utf-8") as f:
        r = json.load(f)
    if not r["accuracy_met"]:
        raise RuntimeError(name + ": the goal was not met")
    return r["photons"], r["seconds"], r["targets"][0]["mean_lux"]


def main() -> None:
    """Runs the four cases and prints the table."""
    cli = sys.argv[1] if len(sys.argv) > 1 else "build/NativeSolver/cli/lightsolver"
    print("| outside | sky enters | photons to ±2 % worst cell | seconds | floor mean (lx) |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        for obstructed in (False, True):
            for portal in (True, False):
                photons, seconds, mean = run(cli, folder, portal, obstructed)
                print(f"| {'black overhang + neighbour' if obstructed else 'open'} | "
                      f"{'portal' if portal else 'site disc'} | {photons:,} | {seconds:.2f} | "
                      f"{mean:.1f} |", flush=True)


if __name__ == "__main__":
    main()
