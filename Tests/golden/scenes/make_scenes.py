"""Writes the golden scenes of this folder (Tests/golden/README.md): `lamps.json` (every
luminaire type, every target type, groups, requirements near their bounds) and
`materials.json` (every material kind). Run with /usr/bin/python3 from anywhere; the output is
deterministic. Changing a scene changes its goldens: regenerate them in the same commit."""
import json
from pathlib import Path

HERE = Path(__file__).resolve().parent


def quad(name, material, corner, e1, e2):
    """A parallelogram mesh corner + s e1 + t e2, front toward e1 x e2."""
    c = corner
    v = [c, [c[i] + e1[i] for i in range(3)], [c[i] + e1[i] + e2[i] for i in range(3)],
         [c[i] + e2[i] for i in range(3)]]
    return {"name": name, "material": material, "vertices": v, "triangles": [[0, 1, 2], [0, 2, 3]]}


def box(name, material, lo, hi):
    """A closed box with outward normals (a solid body for glass)."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
         [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]]
    t = [[0, 2, 1], [0, 3, 2],  # bottom, facing -z
         [4, 5, 6], [4, 6, 7],  # top, +z
         [0, 1, 5], [0, 5, 4],  # y0 side, -y
         [2, 3, 7], [2, 7, 6],  # y1 side, +y
         [1, 2, 6], [1, 6, 5],  # x1 side, +x
         [3, 0, 4], [3, 4, 7]]  # x0 side, -x
    return {"name": name, "material": material, "vertices": v, "triangles": t}


def room(w, d, h):
    """Floor, ceiling and four walls of a w x d x h room, each facing into the room."""
    return [quad("floor", "floor", [0, 0, 0], [w, 0, 0], [0, d, 0]),
            quad("ceiling", "ceiling", [0, 0, h], [0, d, 0], [w, 0, 0]),
            quad("wall south", "wall", [0, 0, 0], [0, 0, h], [w, 0, 0]),
            quad("wall north", "wall", [0, d, 0], [w, 0, 0], [0, 0, h]),
            quad("wall west", "wall", [0, 0, 0], [0, d, 0], [0, 0, h]),
            quad("wall east", "wall", [w, 0, 0], [0, 0, h], [0, d, 0])]


def lamps():
    """A 4 x 3 x 2.8 m room lit by one luminaire of every type (four groups), with a surface,
    two grids, an observer and an observer grid; requirements put verdicts near their bounds
    (the values were picked from a first run so that both backends give pass, fail and
    undecided lines; see Tests/golden/README.md)."""
    lum = "../../../Resources/luminaires/"
    luminaires = [
        {"name": "panel", "type": "area", "group": "general", "flux_lm": 3000,
         "corner": [1.2, 1.6, 2.79], "edge1": [0.6, 0, 0], "edge2": [0, -0.6, 0]},
        {"name": "batwing", "type": "photometric", "group": "general",
         "file": lum + "batwing_panel.ldt", "position": [2.8, 2.0, 2.78], "rotation_deg": 30},
        {"name": "spot", "type": "spot", "group": "accent", "flux_lm": 800,
         "position": [3.0, 1.0, 2.7], "direction": [0.2, 0.1, -1], "beam_angle_deg": 30,
         "field_angle_deg": 60},
        {"name": "bulb", "type": "point", "group": "accent", "flux_lm": 500,
         "position": [0.8, 2.4, 2.5]},
        {"name": "downlight", "type": "photometric", "group": "downlights",
         "file": lum + "downlight.ies", "position": [2.0, 0.7, 2.78], "flux_lm": 1200},
        {"name": "tilted", "type": "photometric", "group": "downlights",
         "file": "downlight_tilt.ies", "position": [3.6, 2.6, 2.6], "aim": [-0.5, -0.3, -1],
         "rotation_deg": 15},
        {"name": "sun", "type": "directional", "group": "sun", "illuminance_lx": 3000,
         "direction": [0.6, 0.2, -0.7], "corner": [0.05, 1.0, 1.6], "edge1": [0, 0.8, 0],
         "edge2": [0, 0, 0.8]},
    ]
    targets = [
        {"name": "desk", "type": "surface", "mesh": "desk top",
         "requirements": {"em_lux": 659}},
        {"name": "workplane", "type": "grid", "corner": [0.5, 0.5, 0.8], "edge1": [3, 0, 0],
         "edge2": [0, 2, 0], "cells": [6, 4],
         "requirements": {"em_lux": 888, "u0": 0.52, "emin_lux": 447}},
        {"name": "east wall", "type": "grid", "corner": [3.99, 0.5, 0.5], "edge1": [0, 0, 1.5],
         "edge2": [0, 2, 0], "cells": [3, 4], "requirements": {"ud": 0.61}},
        {"name": "seated", "type": "observer", "position": [0.6, 1.5, 1.2],
         "view_direction": [1, 0, 0], "requirements": {"ugr_max": 24.7}},
        {"name": "eyes", "type": "observer_grid", "positions": [[0.6, 0.8, 1.2], [3.3, 2.2, 1.7]],
         "view_step_deg": 90, "requirements": {"ugr_max": 22}},
    ]
    return {
        "format": "lightsolver.scene/1",
        "metadata": {"description": "golden: every luminaire and target type (make_scenes.py)"},
        "materials": {"floor": {"type": "diffuse", "reflectance": 0.2},
                      "wall": {"type": "diffuse", "reflectance": 0.5},
                      "ceiling": {"type": "diffuse", "reflectance": 0.7},
                      "oak": {"type": "diffuse", "reflectance": 0.35}},
        "meshes": room(4, 3, 2.8) + [
            quad("desk top", "oak", [2.2, 1.8, 0.75], [1.0, 0, 0], [0, 0.6, 0])],
        "luminaires": luminaires,
        "targets": targets,
        "settings": {"photons": 200000, "seed": 7, "contributions": True},
    }


def materials():
    """Every material kind under two lamps, open to a black sky so paths end quickly: a
    Lambertian floor, a mirror wall, a solid glass block, a thin tinted pane, a glossy table."""
    meshes = [
        quad("floor", "concrete", [0, 0, 0], [4, 0, 0], [0, 4, 0]),
        quad("mirror", "mirror", [4, 0, 0], [0, 0, 2.5], [0, 4, 0]),
        box("block", "crystal", [0.6, 0.6, 0], [1.4, 1.4, 0.5]),
        quad("pane", "window", [2.0, 0.5, 0.2], [0, 1.5, 0], [0, 0, 1.5]),
        quad("table", "lacquer", [2.6, 2.4, 0.7], [1.0, 0, 0], [0, 1.0, 0]),
    ]
    luminaires = [
        {"name": "over block", "type": "spot", "flux_lm": 2000, "position": [1.0, 1.0, 2.5],
         "direction": [0, 0, -1], "beam_angle_deg": 20, "field_angle_deg": 40},
        {"name": "lamp", "type": "point", "flux_lm": 3000, "position": [1.2, 2.6, 1.8]},
    ]
    targets = [
        {"name": "under block", "type": "grid", "corner": [0.5, 0.5, 0.001], "edge1": [1, 0, 0],
         "edge2": [0, 1, 0], "cells": [4, 4]},
        {"name": "behind pane", "type": "grid", "corner": [2.3, 0.5, 0.3], "edge1": [0, 0, 1.2],
         "edge2": [0, 1.5, 0], "cells": [2, 3]},
        {"name": "table", "type": "surface", "mesh": "table"},
        {"name": "above table", "type": "grid", "corner": [2.4, 2.2, 1.8], "edge1": [0, 1.4, 0],
         "edge2": [1.4, 0, 0], "cells": [3, 3]},
        {"name": "mirror", "type": "surface", "mesh": "mirror"},
        {"name": "floor", "type": "surface", "mesh": "floor"},
    ]
    return {
        "format": "lightsolver.scene/1",
        "metadata": {"description": "golden: every material kind (make_scenes.py)"},
        "materials": {
            "concrete": {"type": "diffuse", "reflectance": 0.4},
            "mirror": {"type": "mirror", "reflectance": 0.85},
            "crystal": {"type": "glass", "ior": 1.5, "transmittance": 0.9},
            "window": {"type": "glass", "ior": 1.52, "transmittance": 0.8, "thin": True},
            "lacquer": {"type": "glossy", "reflectance": 0.2, "specular": 0.6, "roughness": 0.3},
        },
        "meshes": meshes,
        "luminaires": luminaires,
        "targets": targets,
        "settings": {"photons": 200000, "seed": 3},
    }


def main() -> None:
    for name, scene in (("lamps", lamps()), ("materials", materials())):
        text = json.dumps(scene, indent=1)
        (HERE / f"{name}.json").write_text(text + "\n")
        print("wrote", HERE / f"{name}.json")


if __name__ == "__main__":
    main()
