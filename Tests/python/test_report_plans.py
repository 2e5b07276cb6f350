"""The report's plans and picture of the model (lightsolver_report.pictures, docs/report.md):
floor plans to scale from a horizontal section of the scene's meshes, with the luminaires
named and aimed, the calculation areas and the observers; the false-colour axonometric drawing
or the workbench's 3D-view screenshot. Geometry is checked on the functions that compute it
and on the SVG the page carries (lengths read back from the drawing's paths)."""
import json
import math
import os
import re
import struct
import subprocess
import sys
import types
from pathlib import Path

import numpy as np
import pytest

from lightsolver_report import ReportError, build, pictures, render_html
from lightsolver_report.floorplan import (MAX_H_MM, MAX_W_MM, arrow_end, bar_length,
                                          choose_scale, observer_arrows)
from lightsolver_report.meshes import clean, load_meshes, read_mesh_file
from lightsolver_report.planitems import direction_name, luminaire_row, plan_items
from lightsolver_report.section import find_levels, section, solids

from conftest import SOURCE_DIR

FIXTURES = Path(__file__).resolve().parent / "fixtures" / "report"
LAMPS = SOURCE_DIR / "Tests" / "golden" / "scenes" / "lamps.json"
DATE = "2026-01-01"
#: The plans section's heading, numbered among the report's sections.
PLANS_HEADING = r"<h2>\d+ Plans and view of the model</h2>"
PT_PER_MM = 72.0 / 25.4


# --- helpers ----------------------------------------------------------------------------------

def box(x0, y0, z0, x1, y1, z1):
    """A closed box with outward normals: 8 vertices, 12 triangles."""
    v = [[x, y, z] for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)]
    t = [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
         [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]]
    return v, t


def mesh(name, geometry, material="wall"):
    v, t = geometry
    return {"name": name, "material": material, "vertices": v, "triangles": t}


def walled_room(extra_meshes=(), luminaires=None, targets=None, metadata=None):
    """A 6 m × 4 m room, 3 m high, four 0.2 m thick wall boxes touching at the corners, a
    floor and a ceiling."""
    meshes = [mesh("south", box(-0.2, -0.2, 0, 6.2, 0, 3)),
              mesh("north", box(-0.2, 4, 0, 6.2, 4.2, 3)),
              mesh("west", box(-0.2, 0, 0, 0, 4, 3)),
              mesh("east", box(6, 0, 0, 6.2, 4, 3)),
              mesh("floor", ([[0, 0, 0], [6, 0, 0], [6, 4, 0], [0, 4, 0]],
                             [[0, 1, 2], [0, 2, 3]]), "floor"),
              mesh("ceiling", ([[0, 0, 3], [0, 4, 3], [6, 4, 3], [6, 0, 3]],
                               [[0, 1, 2], [0, 2, 3]]))] + list(extra_meshes)
    return {"format": "lightsolver.scene/1",
            "materials": {"wall": {"type": "diffuse", "reflectance": 0.5},
                          "floor": {"type": "diffuse", "reflectance": 0.2}},
            "meshes": meshes,
            "luminaires": luminaires if luminaires is not None else [
                {"name": "L1", "type": "point", "flux_lm": 1000, "position": [3, 2, 2.9]}],
            "targets": targets if targets is not None else [
                {"name": "work", "type": "grid", "corner": [0.5, 0.5, 0.8],
                 "edge1": [5, 0, 0], "edge2": [0, 3, 0], "cells": [5, 3]}],
            "metadata": metadata or {}}


def plans_of(scene, base_dir="."):
    """The plans of a scene (and its items), as the report builds them."""
    labels = pictures._labels(scene)
    meshes, notes = load_meshes(scene, str(base_dir), labels)
    items = plan_items(scene, meshes, labels)
    return pictures.build_plans(scene, meshes, items), meshes, items, notes


def path_extent(svg, gid):
    """(width, height) in SVG units (pt) of the path drawn in the group with id ``…-gid``."""
    match = re.search(r'<g id="[^"]*-%s">\s*<path d="([^"]+)"' % re.escape(gid), svg)
    assert match, f"no group {gid} in the drawing"
    numbers = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", match.group(1))]
    xs, ys = numbers[0::2], numbers[1::2]
    return max(xs) - min(xs), max(ys) - min(ys)


def path_ends(svg, gid):
    """An arrow's start and tip: the first point of the path in the group ``…-gid`` and the
    point farthest from it (SVG units, y down; the head's corners are nearer)."""
    match = re.search(r'<g id="[^"]*-%s">\s*<path d="([^"]+)"' % re.escape(gid), svg)
    assert match, f"no group {gid} in the drawing"
    numbers = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", match.group(1))]
    points = np.array(numbers[:len(numbers) // 2 * 2]).reshape(-1, 2)
    return points[0], points[np.argmax(np.linalg.norm(points - points[0], axis=1))]


def fake_report(areas=()):
    return types.SimpleNamespace(areas=list(areas))


# --- scale ------------------------------------------------------------------------------------

def test_the_scale_bar_measures_the_scenes_metres():
    scene = json.loads((FIXTURES / "room.scene.json").read_text())
    plans, *_ = plans_of(scene, FIXTURES)
    (plan,) = plans
    # The workplane is 5 m along x: the scale bar's blocks together are bar_m long on the same
    # drawing, and both are 1000/scale mm per metre on paper (the SVG is printed at its size).
    grid_w, _ = path_extent(plan.svg, "grid0")
    bar_w = sum(path_extent(plan.svg, f"scalebar{i}")[0] for i in range(10)
                if f"-scalebar{i}\"" in plan.svg)
    assert bar_w / grid_w == pytest.approx(plan.bar_m / 5.0, rel=1e-3)
    assert grid_w / PT_PER_MM == pytest.approx(5.0 * 1000.0 / plan.scale, rel=1e-3)
    assert plan.scale == 50 and plan.bar_m == 2.0
    assert f"Scale 1:{plan.scale} (A4)" in plan.svg
    width_pt = float(re.search(r'<svg[^>]* width="([\d.]+)pt"', plan.svg).group(1))
    assert width_pt / PT_PER_MM <= 180.0  # fits the page at its size: printed to scale


@pytest.mark.parametrize("w, h", [(6.8, 4.8), (41.5, 21.5), (0.8, 0.5), (300.0, 10.0),
                                  (5.0, 60.0)])
def test_the_scale_is_the_smallest_standard_one_that_fits_the_page(w, h):
    n = choose_scale(w, h)
    assert w * 1000.0 / n <= MAX_W_MM + 1e-9 and h * 1000.0 / n <= MAX_H_MM + 1e-9
    bar = bar_length(w)
    assert bar <= w / 3.0 and bar > w / 3.0 / 2.5 - 1e-12  # a round length near a third
    assert round(bar / 10 ** math.floor(math.log10(bar) + 1e-9)) in (1, 2, 5)


# --- section ----------------------------------------------------------------------------------

def test_the_section_of_a_box_room_gives_its_four_walls():
    scene = walled_room()
    meshes, _ = load_meshes(scene, ".")
    (level,) = find_levels(np.concatenate([m.corners for m in meshes]),
                           [(0.8, (0.5, 5.5, 0.5, 3.5))], None)
    assert level.floor_z == 0.0 and level.cut_z == pytest.approx(1.0)
    cut = section(meshes, level)
    fill, rest = solids(cut.walls)
    assert not rest and len(fill) == 4
    found = sorted(tuple(np.round(np.concatenate([loop.min(axis=0), loop.max(axis=0)]), 6))
                   for loop in fill)
    assert found == sorted([(-0.2, -0.2, 6.2, 0.0), (-0.2, 4.0, 6.2, 4.2),
                            (-0.2, 0.0, 0.0, 4.0), (6.0, 0.0, 6.2, 4.0)])
    # floor below the cut (and the walls' feet), the ceiling above it: not seen from above
    seen = [layer.mesh.name for layer in cut.layers]
    assert "floor" in seen and "ceiling" not in seen


def test_a_room_of_single_wall_faces_is_outlined_not_filled():
    scene = json.loads(LAMPS.read_text())  # four wall quads facing the room
    meshes, _ = load_meshes(scene, LAMPS.parent)
    (level,) = find_levels(np.concatenate([m.corners for m in meshes]),
                           [(0.8, (0.5, 3.5, 0.5, 2.5))], None)
    fill, rest = solids(section(meshes, level).walls)
    assert not fill and len(rest) == 1 and rest[0].closed
    assert np.allclose(np.sort(rest[0].points, axis=0)[[0, -1]], [[0, 0], [4, 3]])


def test_a_wall_ring_is_filled_around_the_room_and_windows_are_glass():
    # One closed ring (outer 6.4 × 4.4, inner 6 × 4) as a mesh, with a pane in the south wall.
    outer = [[-0.2, -0.2], [6.2, -0.2], [6.2, 4.2], [-0.2, 4.2]]
    inner = [[0, 0], [6, 0], [6, 4], [0, 4]]
    v, t = [], []
    for k in range(4):  # each side of the ring a band: outer edge, inner edge, both heights
        a, b, c, d = outer[k], outer[(k + 1) % 4], inner[(k + 1) % 4], inner[k]
        n = len(v)
        v += [a + [0], b + [0], c + [0], d + [0], a + [3], b + [3], c + [3], d + [3]]
        t += [[n, n + 1, n + 5], [n, n + 5, n + 4], [n + 3, n + 7, n + 6], [n + 3, n + 6, n + 2]]
    ring = {"name": "walls", "material": "wall", "vertices": v, "triangles": t}
    pane = mesh("pane", ([[2, -0.1, 0.9], [4, -0.1, 0.9], [4, -0.1, 2.2], [2, -0.1, 2.2]],
                         [[0, 1, 2], [0, 2, 3]]), "glass")
    scene = walled_room()
    scene["meshes"] = [ring, pane] + scene["meshes"][4:]
    scene["materials"]["glass"] = {"type": "glass", "thin": True}
    meshes, _ = load_meshes(scene, ".")
    (level,) = find_levels(np.concatenate([m.corners for m in meshes]),
                           [(0.8, (0.5, 5.5, 0.5, 3.5))], None)
    cut = section(meshes, level)
    # the ring's outer and inner faces (its normals face both ways: it is not closed at the top
    # and bottom here, so the thinness decides) fill as one wall with the room as its hole
    fill, rest = solids(cut.walls)
    assert len(fill) == 2 and not rest
    assert len(cut.glass) == 1 and np.allclose(sorted(cut.glass[0].points[:, 0]), [2, 4])


def test_storeys_each_get_a_plan_with_their_own_luminaires():
    upper = walled_room()
    for m in upper["meshes"]:
        m["name"] += " 2"
        m["vertices"] = [[x, y, z + 3.5] for x, y, z in m["vertices"]]
    scene = walled_room(extra_meshes=upper["meshes"] + [
        mesh("slab", box(-0.2, -0.2, 3.0, 6.2, 4.2, 3.5))],
        luminaires=[{"name": "down", "type": "point", "flux_lm": 1, "position": [3, 2, 2.9]},
                    {"name": "up", "type": "point", "flux_lm": 1, "position": [3, 2, 6.4]}],
        targets=[{"name": "w0", "type": "grid", "corner": [0.5, 0.5, 0.8], "edge1": [5, 0, 0],
                  "edge2": [0, 3, 0], "cells": [5, 3]},
                 {"name": "w1", "type": "grid", "corner": [0.5, 0.5, 4.3], "edge1": [5, 0, 0],
                  "edge2": [0, 3, 0], "cells": [5, 3]}])
    plans, *_ = plans_of(scene)
    assert [p.floor_z for p in plans] == [0.0, 3.5]
    assert [[r.label for r in p.luminaires] for p in plans] == [["down"], ["up"]]
    assert [p.areas for p in plans] == [["w0"], ["w1"]]
    assert plans[1].title == "Floor plan, storey at +3.50 m"


# --- what the plan marks ------------------------------------------------------------------------

def test_every_luminaire_appears_with_the_name_the_user_gave():
    scene = json.loads(LAMPS.read_text())
    scene["metadata"]["labels"] = {"bulb": "Pendant bulb & shade"}
    (plan,), *_ = plans_of(scene, LAMPS.parent)
    names = [lum["name"] for lum in scene["luminaires"]]
    shown = ["Pendant bulb &amp; shade" if n == "bulb" else n for n in names]
    for text in shown:
        assert f">{text}<" in plan.svg
    assert [r.label for r in plan.luminaires] == [
        "Pendant bulb & shade" if n == "bulb" else n for n in names]
    html = render_html(scene, json.loads(
        (SOURCE_DIR / "Tests" / "golden" / "lamps.embree.results.json").read_text()),
        scene_path=LAMPS, date=DATE)
    plans_html = html[re.search(PLANS_HEADING, html).start():]
    assert "Pendant bulb &amp; shade" in plans_html and ">bulb<" not in plans_html


def test_many_luminaires_are_numbered_and_the_table_names_them():
    lums = [{"name": f"downlight {i}", "type": "point", "flux_lm": 100,
             "position": [0.5 + 0.7 * (i % 8), 0.4 + 0.6 * (i // 8), 2.9]} for i in range(48)]
    (plan,), *_ = plans_of(walled_room(luminaires=lums))
    assert plan.numbered
    for i, row in enumerate(plan.luminaires):
        assert row.number == i + 1 and row.label == f"downlight {i}"
        assert f">{i + 1}<" in plan.svg
    assert ">downlight 0<" not in plan.svg


def test_aimed_luminaires_point_to_their_aiming_point_on_the_floor():
    scene = json.loads(LAMPS.read_text())
    plans, _, items, _ = plans_of(scene, LAMPS.parent)
    marks = {m.name: m for m in items.luminaires}
    tilted = marks["tilted"]  # aim (-0.5, -0.3, -1) from z 2.6: the floor at (2.3, 1.82)
    assert np.allclose(tilted.aiming_point(0.0), [3.6 - 1.3, 2.6 - 0.78, 0.0])
    row = luminaire_row(tilted, 0.0)
    assert row.aiming == "tilted 30° to (2.30, 1.82) on the floor; turned 15°"
    assert luminaire_row(marks["downlight"], 0.0).aiming == "straight down"
    assert luminaire_row(marks["bulb"], 0.0).aiming.startswith("–")
    assert not marks["panel"].aimed and not marks["batwing"].aimed
    # In the drawing: an arrow from the luminaire to that point, at the plan's scale.
    svg = plans[0].svg
    start, tip = path_ends(svg, f"aim{tilted.number}")
    drawn = (tip - start) * np.array([1, -1])  # SVG y points down
    plan_vector = np.array([2.3 - 3.6, 1.82 - 2.6])
    assert drawn / np.linalg.norm(drawn) == pytest.approx(plan_vector / np.linalg.norm(
        plan_vector), abs=0.02)
    assert np.linalg.norm(drawn) / PT_PER_MM == pytest.approx(
        np.linalg.norm(plan_vector) * 1000 / plans[0].scale, rel=0.05)
    assert "aim" + str(marks["downlight"].number) + '"' not in svg


def test_observer_arrows_point_their_way():
    scene = json.loads(LAMPS.read_text())
    (plan,), _, items, _ = plans_of(scene, LAMPS.parent)
    seated, eyes = items.observers
    box_m = plan.extent
    (start, tip), = observer_arrows(seated, 0.5, box_m)
    assert np.allclose(start, [0.6, 1.5]) and np.allclose(tip, [1.1, 1.5])  # view +x
    arrows = observer_arrows(eyes, 0.3, box_m)
    assert len(arrows) == 2 * 4  # two eyes, every 90°
    for (s, t), d in zip(arrows, [d for _ in range(2) for d in eyes.directions]):
        v = (t - s) / np.linalg.norm(t - s)
        assert np.allclose(v, d[:2] / np.linalg.norm(d[:2]))
    # a long arrow stops at the plan's edge, still pointing its way
    tip = arrow_end(np.array([0.6, 1.5, 1.2]), np.array([-1.0, 0.0, 0.0]), 50.0, box_m)
    assert np.allclose(tip, [box_m[0], 1.5])
    # drawn: one arrow per line of sight, the seated eye's along +x
    for i, mark in enumerate(items.observers):
        for j in range(len(mark.positions) * len(mark.directions)):
            assert f"-sight{i}-{j}\"" in plan.svg
    s, t = path_ends(plan.svg, "sight0-0")
    assert t[0] > s[0] and abs(t[1] - s[1]) < 1e-6
    assert [(r.label, r.views) for r in plan.observers] == [
        ("seated", "+x"), ("eyes", "+x, +y, −x, −y")]


def test_directions_are_named_by_the_compass_when_north_is_known():
    east = np.array([1.0, 0.0, 0.0])
    assert direction_name(east) == "+x"
    assert direction_name(east, 0.0) == "east (90°)"
    assert direction_name(east, 90.0) == "south (180°)"  # north along −x
    assert direction_name(np.array([0.0, 0.0, -1.0])) == "down"
    scene = json.loads((FIXTURES / "room.scene.json").read_text())
    scene["metadata"]["north_deg"] = 30
    (plan,), *_ = plans_of(scene, FIXTURES)
    assert '-north">' in plan.svg and ">N<" in plan.svg
    (plain,), *_ = plans_of(json.loads((FIXTURES / "room.scene.json").read_text()), FIXTURES)
    assert "-north\"" not in plain.svg


# --- inputs that are not the usual ------------------------------------------------------------

def test_a_scene_without_grids_or_surfaces_still_gets_a_plan_and_a_picture():
    scene = walled_room(targets=[{"name": "eye", "type": "observer", "position": [1, 1, 1.2],
                                  "view_direction": [0, 1, 0]}])
    report = fake_report()
    pictures.attach(report, scene, ".")
    (plan,) = report.plans
    assert plan.areas == [] and [r.label for r in plan.luminaires] == ["L1"]
    assert report.model_picture.shown and "<svg" in report.model_picture.svg
    assert "E [lx]" not in report.model_picture.svg  # nothing in false colour: no legend


def test_a_scene_without_geometry_gets_a_plan_of_its_luminaires_and_no_picture():
    scene = walled_room()
    scene["meshes"] = []
    report = fake_report()
    pictures.attach(report, scene, ".")
    (plan,) = report.plans
    assert ">L1<" in plan.svg and ">work<" in plan.svg
    assert not report.model_picture.shown and report.model_picture.svg == ""
    assert "nan" not in plan.svg.lower()


def test_degenerate_geometry_is_left_out_without_nan():
    bad = {"name": "junk", "material": "wall",
           "vertices": [[1, 1, 0], [1, 1, 0], [2, 2, 0], [3, 3, 0], [float("nan"), 0, 0],
                        [1, 1, 1], [1, 1, 1.5]],
           "triangles": [[0, 1, 2], [0, 2, 3], [4, 0, 2], [5, 5, 6], [0, 1, 9]]}
    flat = mesh("sliver", ([[1, 1, 0.5], [2, 1, 0.5], [3, 1, 0.5]], [[0, 1, 2]]))
    scene = walled_room(extra_meshes=[bad, flat])
    meshes, _ = load_meshes(scene, ".")
    by_name = {m.name: m for m in meshes}
    assert len(by_name["junk"].triangles) == 0 and len(by_name["sliver"].triangles) == 0
    assert len(clean(np.zeros((3, 3)), [[0, 1, 2]])) == 0
    report = fake_report()
    pictures.attach(report, scene, ".")
    for svg in [p.svg for p in report.plans] + [report.model_picture.svg]:
        text = re.sub(r"data:image/png;base64,[^\"]*", "", svg).lower()
        assert not re.search(r"\bnan\b|\binf\b", text)


def test_a_mesh_file_that_cannot_be_read_is_said_without_its_name(tmp_path):
    scene = walled_room(extra_meshes=[{"name": "cupboard", "material": "wall",
                                       "file": "missing/cupboard.ply"}])
    scene["metadata"]["labels"] = {"cupboard": "Tall cupboard"}
    report = fake_report()
    pictures.attach(report, scene, str(tmp_path))
    assert report.picture_notes == [
        "“Tall cupboard” is not drawn: its geometry could not be read"]
    assert len(report.plans) == 1


def test_ply_and_obj_files_draw_like_inline_geometry(tmp_path):
    v, t = box(2, 1, 0, 3, 2, 1.5)  # a cupboard cut by the section
    # binary PLY as the workbench writes it (double coordinates, uchar/uint lists)
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty double x\n"
              "property double y\nproperty double z\nelement face 12\n"
              "property list uchar uint vertex_indices\nend_header\n").encode()
    body = b"".join(struct.pack("<3d", *p) for p in v) + b"".join(
        struct.pack("<B3I", 3, *f) for f in t)
    (tmp_path / "cupboard.ply").write_bytes(header + body)
    # ASCII PLY with quads (fanned) and OBJ with negative indices: the same box
    quads = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    (tmp_path / "ascii.ply").write_text(
        "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
        "property float z\nelement face 6\nproperty list uchar int vertex_indices\n"
        "end_header\n" + "".join(" ".join(map(str, p)) + "\n" for p in v)
        + "".join(f"4 {' '.join(map(str, q))}\n" for q in quads))
    (tmp_path / "box.obj").write_text("".join(f"v {' '.join(map(str, p))}\n" for p in v) + "".join(
        "f " + " ".join(str(i - 8) for i in f) + "\n" for f in t))
    for name in ("cupboard.ply", "ascii.ply", "box.obj"):
        vertices, triangles = read_mesh_file(str(tmp_path / name))
        assert np.allclose(vertices, v) and len(triangles) == 12
    inline = walled_room(extra_meshes=[mesh("cupboard", (v, t))])
    from_file = walled_room(extra_meshes=[{"name": "cupboard", "material": "wall",
                                           "file": "cupboard.ply"}])
    a, *_ = plans_of(inline)
    b, *_ = plans_of(from_file, tmp_path)
    assert a[0].svg == b[0].svg
    moved = walled_room(extra_meshes=[{"name": "cupboard", "material": "wall",
                                       "file": "box.obj",
                                       "transform": [[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0],
                                                     [0, 0, 0, 1]]}])
    meshes, _ = load_meshes(moved, str(tmp_path))
    assert np.allclose(meshes[-1].vertices.min(axis=0), [3, 1, 0])


# --- the picture of the model -----------------------------------------------------------------

def test_the_picture_colours_grids_and_surfaces_by_their_results():
    results = json.loads((FIXTURES / "room.results.json").read_text())
    report = build(FIXTURES / "room.scene.json", results, date=DATE)
    picture = report.model_picture
    assert picture.shown and not picture.view_png and "Axonometric" in picture.caption
    painting, norm, cmap = picture.painting()
    targets = {t["name"]: t for t in results["targets"]}
    # the workplane's cells on its plane (the only cut at 0.8 m), each in its value's colour
    (plane,) = [p for h, p in zip(painting.cuts, painting.planes) if abs(h - 0.8) < 1e-9]
    (quads, rgba), = plane
    lux = [c["lux"] for c in targets["workplane"]["cells"]]
    assert len(quads) == len(lux) == 63
    assert np.allclose(rgba, cmap(norm(np.array(lux))))
    assert np.allclose(quads[:, :, 2], 0.8)
    # the colour scale spans every value shown, surfaces' means included
    shown = lux + [targets["floor"]["mean_lux"], targets["desk top"]["mean_lux"]]
    assert norm.vmin <= min(shown) and norm.vmax >= max(shown)
    # surfaces with results in their mean's colour, the others grey
    colours = np.concatenate([c for slab in painting.slabs for _, c in slab])
    floor_colour = cmap(norm(targets["floor"]["mean_lux"]))
    desk_colour = cmap(norm(targets["desk top"]["mean_lux"]))
    coloured = np.all(np.isclose(colours, floor_colour), axis=1) | np.all(
        np.isclose(colours, desk_colour), axis=1)
    assert coloured.any()
    grey = colours[~coloured]
    assert len(grey) and np.allclose(grey[:, 0], grey[:, 1]) and np.allclose(grey[:, 1],
                                                                             grey[:, 2])
    svg = picture.svg
    assert "<image" in svg and "E [lx]" in svg  # the painting is one raster, the legend text
    assert svg == report.model_picture.svg  # made once


def test_a_3d_view_screenshot_replaces_the_drawing(tmp_path):
    results = json.loads((FIXTURES / "room.results.json").read_text())
    png = tmp_path / "view.png"
    png.write_bytes(b"\x89PNG\r\n\x1a\n" + b"\x00" * 16)
    report = build(FIXTURES / "room.scene.json", results, date=DATE)
    report.view_png = str(png)
    html = report.model_picture.__html__()
    assert html.startswith('<img class="model-view" src="data:image/png;base64,iVBORw0KGgo')
    assert "3D view" in report.model_picture.caption
    png.write_text("not a picture")
    with pytest.raises(ReportError, match="not a PNG"):
        report.model_picture.__html__()
    report.view_png = str(tmp_path / "gone.png")
    with pytest.raises(ReportError, match="cannot read the picture"):
        report.model_picture.__html__()


def test_plans_are_byte_reproducible_across_processes():
    code = ("import json, sys, lightsolver_report\n"
            "from pathlib import Path\n"
            "F = Path(sys.argv[1])\n"
            "r = lightsolver_report.build(F / 'lamps.json', json.loads(Path(sys.argv[2])"
            ".read_text()), date='2026-01-01')\n"
            "sys.stdout.write(r.plans[0].svg + r.model_picture.svg)\n")
    results = SOURCE_DIR / "Tests" / "golden" / "lamps.embree.results.json"
    outs = []
    for seed in ("1", "2"):
        env = dict(os.environ, PYTHONHASHSEED=seed)
        outs.append(subprocess.run([sys.executable, "-c", code, str(LAMPS.parent), str(results)],
                                   env=env, check=True, capture_output=True, text=True).stdout)
    assert outs[0] == outs[1] and len(outs[0]) > 1000


def test_the_page_holds_the_plans_section_once():
    html = (FIXTURES / "office.report.html").read_text(encoding="utf-8")
    assert len(re.findall(PLANS_HEADING, html)) == 1
    section_html = html[re.search(PLANS_HEADING, html).start():]
    section_html = section_html[:section_html.index("</section>")]
    for name in ("Luminaire01", "Luminaire02", "Luminaire03", "Luminaire04", "Workplane"):
        assert f">{name}<" in section_html
    assert "scene.json" not in section_html and ".ply" not in section_html
