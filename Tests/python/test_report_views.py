"""The plans' top view and the picture of the model where a painter's order is not enough:
a mesh's own hidden edges (a table's legs under its top), rooms turned off the model's axes
(seen from their own corner, drawn as the same room), and the depth buffer that decides what
the picture shows (faces crossing each other, glass). docs/report.md, "Plans and the picture
of the model"."""
import json
import math

import numpy as np
import pytest

from lightsolver_report import pictures
from lightsolver_report.meshes import load_meshes
from lightsolver_report.section import find_levels, section

from test_report_plans import box, fake_report, mesh, walled_room


def _table():
    """A 1.2 × 0.6 m table, 0.72 m high: a 3 cm top over four 5 cm legs, one mesh."""
    parts = [box(2.0, 1.0, 0.69, 3.2, 1.6, 0.72)] + [
        box(x, y, 0.0, x + 0.05, y + 0.05, 0.69) for x in (2.05, 3.1) for y in (1.05, 1.5)]
    v, t = [], []
    for pv, pt in parts:
        t += [[i + len(v) for i in tri] for tri in pt]
        v += pv
    return mesh("table", (v, t), "floor")


def test_a_tables_legs_are_hidden_under_its_top_in_the_plan():
    from lightsolver_report.floorplan import top_view

    meshes, _ = load_meshes(walled_room([_table()]), ".")
    (level,) = find_levels(np.concatenate([m.corners for m in meshes]),
                           [(0.8, (0.5, 5.5, 0.5, 3.5))], None)
    items = top_view(section(meshes, level))
    top_faces = [k for k, (shape, face, _, _, h) in enumerate(items)
                 if face != "none" and h == pytest.approx(0.72)]
    assert len(top_faces) == 2  # the top's two triangles (its underside is below them)
    legs = [k for k, (shape, face, _, _, h) in enumerate(items)
            if face == "none" and h < 0.7 and 2.0 < shape[:, 0].mean() < 3.2
            and 1.0 < shape[:, 1].mean() < 1.6]
    outline = [k for k, (shape, face, _, _, h) in enumerate(items)
               if face == "none" and h == pytest.approx(0.72)]
    assert legs and len(outline) == 4
    # Painted lowest first: every leg edge (and the underside's) before the top hides it, the
    # top's outline after it.
    # (The underside's outline falls on the top's: the four kept are the top's, at 0.72 m.)
    assert max(legs) < min(top_faces) and min(outline) > max(top_faces)


def turn(scene, deg):
    """The scene turned by ``deg`` about the vertical through the origin."""
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))

    def rot(p, point=True):
        return [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]]

    scene = json.loads(json.dumps(scene))
    for m in scene["meshes"]:
        m["vertices"] = [rot(v) for v in m["vertices"]]
    for lum in scene["luminaires"]:
        lum["position"] = rot(lum["position"])
    for t in scene["targets"]:
        for key in ("corner", "edge1", "edge2", "position", "view_direction"):
            if key in t:
                t[key] = rot(t[key])
    return scene


def _image(report, size=(400, 300)):
    """The picture's depth-buffered image at ``size`` pixels, over its own extent."""
    from lightsolver_report.axonometric import AZIMUTH_DEG, projected, rasterise

    picture = report.model_picture
    painting, _, _ = picture.painting()
    flat, depth, colours = projected(painting, AZIMUTH_DEG + picture.angle)
    pts = flat.reshape(-1, 2)
    bounds = (pts[:, 0].min(), pts[:, 0].max(), pts[:, 1].min(), pts[:, 1].max())
    return rasterise(flat, depth, colours, bounds, *size)


@pytest.mark.parametrize("deg", [30.0, -20.0, 44.0])
def test_a_room_turned_off_the_axes_is_drawn_as_the_same_room(deg):
    # The same room with a table, along the axes and turned: seen from its own corner, with
    # its own near walls left out, the drawing is the same (but for pixels on edges).
    straight, turned = fake_report(), fake_report()
    pictures.attach(straight, walled_room([_table()]), ".")
    pictures.attach(turned, turn(walled_room([_table()]), deg), ".")
    expected = (deg + 45.0) % 90.0 - 45.0  # the room's walls modulo 90°
    assert straight.model_picture.angle == 0.0
    assert turned.model_picture.angle == pytest.approx(expected, abs=1e-6)
    a, b = _image(straight), _image(turned)
    assert (a[..., 3] > 0).mean() > 0.3  # the room fills much of the picture
    same = np.all(np.abs(a - b) < 1e-9, axis=2)
    assert same.mean() > 0.99
    assert "lower left" in turned.model_picture.caption


def test_the_depth_buffer_shows_each_of_two_crossing_faces_where_it_is_nearer():
    from lightsolver_report.zbuffer import render

    # Two squares crossing along x = 50: red nearer on the left, blue on the right. No order
    # of the two is right for a painter; the depth buffer is right on both halves.
    red = [[0, 0, 1], [100, 0, -1], [100, 100, -1], [0, 100, 1]]
    blue = [[0, 0, -1], [100, 0, 1], [100, 100, 1], [0, 100, -1]]
    colours = np.array([[1, 0, 0, 1], [0, 0, 1, 1]], dtype=float)
    for order in ([0, 1], [1, 0]):
        image = render(np.array([red, blue], float)[order], colours[order], 100, 100)
        assert np.allclose(image[:, :49], [1, 0, 0, 1]) and np.allclose(image[:, 51:],
                                                                         [0, 0, 1, 1])
    # Glass in front is blended over what is behind it; glass behind is not seen.
    pane = np.array([[[0, 0, 5], [100, 0, 5], [100, 100, 5], [0, 100, 5]]], float)
    wall = pane - [0, 0, 10]
    glass, grey = [0.5, 0.75, 1.0, 0.4], [0.5, 0.5, 0.5, 1.0]
    image = render(np.concatenate([wall, pane]), np.array([grey, glass]), 10, 10)
    assert np.allclose(image[5, 5], [0.5 * 0.6 + 0.5 * 0.4, 0.5 * 0.6 + 0.75 * 0.4,
                                     0.5 * 0.6 + 1.0 * 0.4, 1.0])
    image = render(np.concatenate([pane - [0, 0, 20], wall]), np.array([glass, grey]), 10, 10)
    assert np.allclose(image[5, 5], grey)
