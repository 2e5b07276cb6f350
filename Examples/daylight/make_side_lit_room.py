#!/usr/bin/env python3
"""Writes side_lit_room.scene.json: a side-lit room under the CIE overcast sky, with an EN 17037
daylight-factor grid.

A 6 x 4 x 3 m room (grey ceiling 0.7, walls 0.5, floor 0.3) with one 2.4 x 1.5 m window in the
y = 0 wall, sill at 0.9 m. The sky (the traditional CIE overcast sky, 10 000 lx unobstructed
diffuse horizontal illuminance, ground reflectance 0.2) shines in through a portal in the window
opening glazed with double glazing (tau_v 0.78, frame factor 0.8, maintenance factor 0.9). The
daylight-factor grid lies at 0.85 m with a 0.5 m band along the walls left out and asks for
EN 17037's minimum level at a site whose median external diffuse illuminance is 15 900 lx
(Chicago O'Hare's TMY3 year, docs/daylight.md).
"""
import json
from pathlib import Path

W, D, H = 6.0, 4.0, 3.0  # room width (x), depth (y), height (z) in metres
WX0, WX1, WZ0, WZ1 = 1.8, 4.2, 0.9, 2.4  # the window opening in the y = 0 wall


def quad(corner, e1, e2):
    """Two triangles of corner + s*e1 + t*e2; front = e1 x e2."""
    c = corner
    v = [c, [c[i] + e1[i] for i in range(3)], [c[i] + e1[i] + e2[i] for i in range(3)],
         [c[i] + e2[i] for i in range(3)]]
    return v, [[0, 1, 2], [0, 2, 3]]


def merge(parts):
    """One mesh of several quads."""
    verts, tris = [], []
    for v, t in parts:
        base = len(verts)
        verts += v
        tris += [[base + i for i in tri] for tri in t]
    return {"vertices": verts, "triangles": tris}


def main() -> None:
    """Writes the scene next to this script."""
    walls = [
        quad([0, D, 0], [0, 0, H], [W, 0, 0]),  # back wall y = D, front -y
        quad([0, 0, 0], [0, D, 0], [0, 0, H]),  # x = 0, front +x
        quad([W, 0, 0], [0, 0, H], [0, D, 0]),  # x = W, front -x
        quad([0, 0, 0], [0, 0, H], [WX0, 0, 0]),  # window wall, left of the opening
        quad([WX1, 0, 0], [0, 0, H], [W - WX1, 0, 0]),  # right of it
        quad([WX0, 0, 0], [0, 0, WZ0], [WX1 - WX0, 0, 0]),  # below it
        quad([WX0, 0, WZ1], [0, 0, H - WZ1], [WX1 - WX0, 0, 0]),  # above it
    ]
    band = 0.5
    scene = {
        "format": "lightsolver.scene/1",
        "metadata": {"description": "6 x 4 x 3 m side-lit room, one 2.4 x 1.5 m double-glazed "
                                    "window, CIE overcast sky, EN 17037 daylight-factor grid"},
        "materials": {
            "ceiling": {"type": "diffuse", "reflectance": 0.7},
            "wall": {"type": "diffuse", "reflectance": 0.5},
            "floor": {"type": "diffuse", "reflectance": 0.3},
        },
        "meshes": [
            {"name": "floor", "material": "floor", **merge([quad([0, 0, 0], [W, 0, 0], [0, D, 0])])},
            {"name": "ceiling", "material": "ceiling",
             **merge([quad([0, 0, H], [0, D, 0], [W, 0, 0])])},
            {"name": "walls", "material": "wall", **merge(walls)},
        ],
        "luminaires": [
            {"name": "overcast sky", "type": "sky", "model": "cie_overcast",
             "diffuse_horizontal_lx": 10000, "ground_reflectance": 0.2,
             "portals": [{"corner": [WX0, 0, WZ0], "edge1": [0, 0, WZ1 - WZ0],
                          "edge2": [WX1 - WX0, 0, 0],
                          "glazing": {"transmittance": 0.78, "panes": 2, "frame_factor": 0.8,
                                      "maintenance_factor": 0.9}}]},
        ],
        "targets": [
            {"name": "reference plane", "type": "grid", "quantity": "daylight_factor",
             "corner": [band, band, 0.85], "edge1": [W - 2 * band, 0, 0],
             "edge2": [0, D - 2 * band, 0], "cells": [10, 6],
             "requirements": {"en17037": "minimum", "median_diffuse_lx": 15900}},
            {"name": "floor", "type": "surface", "mesh": "floor"},
        ],
        "settings": {"photons": 2000000, "seed": 1, "confidence": 0.95},
    }
    out = Path(__file__).with_name("side_lit_room.scene.json")
    out.write_text(json.dumps(scene, indent=1) + "\n")
    print(f"wrote {out}")
    write_annual(scene)


def write_annual(scene: dict) -> None:
    """The same room for a year of daylight: its window faces south (north +y), a 20 x 15 cell
    work plane (300 cells, the annual benchmark's), the sky's model unused (the weather file's)."""
    annual = json.loads(json.dumps(scene))
    annual["metadata"]["description"] = (
        "6 x 4 x 3 m side-lit room, one 2.4 x 1.5 m double-glazed south window (north +y), a "
        "300-cell work plane: a year of daylight with lightsolver annual --weather FILE.epw")
    annual["luminaires"][0]["name"] = "sky"
    grid = annual["targets"][0]
    grid.pop("quantity")
    grid.pop("requirements")
    grid["name"] = "work plane"
    grid["cells"] = [20, 15]
    annual["targets"] = [grid]
    out = Path(__file__).with_name("annual_side_lit_room.scene.json")
    out.write_text(json.dumps(annual, indent=1) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
