#!/usr/bin/env python3
"""Writes room.json: a 6 x 4 x 3 m office with a desk, a window and four ceiling panels.

The main example of the README. Room surfaces face inward (their front is the room side), the
desk top is a surface target, and the EN 12464-1 workplane grid sits at 0.80 m with a 0.5 m
band along the walls left out.
"""
import json
import math
from pathlib import Path

W, D, H = 6.0, 4.0, 3.0  # room width (x), depth (y), height (z) in metres


def quad(corner, e1, e2):
    """Two triangles of corner + s*e1 + t*e2; front = e1 x e2."""
    c = corner
    v = [c, [c[i] + e1[i] for i in range(3)], [c[i] + e1[i] + e2[i] for i in range(3)],
         [c[i] + e2[i] for i in range(3)]]
    return v, [[0, 1, 2], [0, 2, 3]]


def merge(parts):
    verts, tris = [], []
    for v, t in parts:
        base = len(verts)
        verts += v
        tris += [[base + i for i in tri] for tri in t]
    return {"vertices": verts, "triangles": tris}


def box(lo, hi):
    """Closed box with outward faces (furniture)."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    X, Y, Z = [x1 - x0, 0, 0], [0, y1 - y0, 0], [0, 0, z1 - z0]
    return [quad([x0, y0, z1], X, Y), quad([x0, y0, z0], Y, X), quad([x0, y0, z0], X, Z),
            quad([x0, y1, z0], Z, X), quad([x0, y0, z0], Z, Y), quad([x1, y0, z0], Y, Z)]


def grid_cells(length_m):
    """EN 12464-1 grid: p = 0.2 * 5^log10(d), n = ceil(d / p)."""
    p = 0.2 * 5 ** math.log10(length_m)
    return math.ceil(length_m / p)


def main() -> None:
    # The window wall (y = 0) is split around a 2 x 1.4 m opening glazed with a thin pane.
    wx0, wx1, wz0, wz1 = 2.0, 4.0, 0.9, 2.3
    walls = [
        quad([0, D, 0], [0, 0, H], [W, 0, 0]),              # back wall y = D, front -y
        quad([0, 0, 0], [0, D, 0], [0, 0, H]),              # x = 0, front +x
        quad([W, 0, 0], [0, 0, H], [0, D, 0]),              # x = W, front -x
        quad([0, 0, 0], [0, 0, H], [wx0, 0, 0]),            # window wall, left of the opening
        quad([wx1, 0, 0], [0, 0, H], [W - wx1, 0, 0]),      # right of it
        quad([wx0, 0, 0], [0, 0, wz0], [wx1 - wx0, 0, 0]),  # below it
        quad([wx0, 0, wz1], [0, 0, H - wz1], [wx1 - wx0, 0, 0]),  # above it
    ]
    bands = 0.5
    nu, nv = grid_cells(W - 2 * bands), grid_cells(D - 2 * bands)
    scene = {
        "format": "lightsolver.scene/1",
        "metadata": {"description": "6 x 4 x 3 m office, four 3400 lm panels, one desk"},
        "materials": {
            "ceiling": {"type": "diffuse", "reflectance": 0.7},
            "wall": {"type": "diffuse", "reflectance": 0.5},
            "floor": {"type": "diffuse", "reflectance": 0.2},
            "oak": {"type": "diffuse", "reflectance": 0.35},
            "window": {"type": "glass", "ior": 1.52, "thin": True},
        },
        "meshes": [
            {"name": "floor", "material": "floor", **merge([quad([0, 0, 0], [W, 0, 0], [0, D, 0])])},
            {"name": "ceiling", "material": "ceiling", **merge([quad([0, 0, H], [0, D, 0], [W, 0, 0])])},
            {"name": "walls", "material": "wall", **merge(walls)},
            {"name": "window", "material": "window",
             **merge([quad([wx0, 0, wz0], [0, 0, wz1 - wz0], [wx1 - wx0, 0, 0])])},
            {"name": "desk body", "material": "oak", **merge(box([2.2, 2.0, 0.0], [3.8, 2.8, 0.72])[1:])},
            {"name": "desk top", "material": "oak",
             **merge([quad([2.2, 2.0, 0.72], [1.6, 0, 0], [0, 0.8, 0])])},
        ],
        "luminaires": [
            {"name": f"panel {i + 1}", "type": "area", "flux_lm": 3400,
             "corner": [x - 0.3, y - 0.3, H], "edge1": [0, 0.6, 0], "edge2": [0.6, 0, 0]}
            for i, (x, y) in enumerate([(1.5, 1.0), (4.5, 1.0), (1.5, 3.0), (4.5, 3.0)])
        ],
        "targets": [
            {"name": "desk top", "type": "surface", "mesh": "desk top"},
            {"name": "workplane", "type": "grid", "corner": [bands, bands, 0.8],
             "edge1": [W - 2 * bands, 0, 0], "edge2": [0, D - 2 * bands, 0], "cells": [nu, nv]},
            {"name": "floor", "type": "surface", "mesh": "floor"},
        ],
        "settings": {"photons": 2000000, "seed": 1, "confidence": 0.95},
    }
    out = Path(__file__).with_name("room.json")
    out.write_text(json.dumps(scene, indent=1) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
