"""lightsolver.direct_sun (docs/daylight.md, "Direct sun at points (for ASE)"): a Chicago year
through numpy against geometry worked here (an overhang; a glazed skylight portal with the glazing
model's Fresnel formula written again), the scene's openings collected, errors named."""
import math

import lightsolver
import numpy as np
import pytest

from conftest import SOURCE_DIR

CHICAGO = SOURCE_DIR / "Tests/native/sun/data/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw"


@pytest.fixture(scope="module")
def year() -> dict:
    return lightsolver.sky_vectors(str(CHICAGO), mf=1)


def plate(scene: lightsolver.Scene, name: str, x0, x1, y0, y1, z) -> None:
    v = np.array([[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]], float)
    scene.add_mesh(name, v, np.array([[0, 1, 2], [0, 2, 3]]), "grey")


def lit_hours(year: dict) -> tuple[np.ndarray, np.ndarray]:
    s = year["sun_direction"].astype(float)
    s /= np.maximum(np.linalg.norm(s, axis=1), 1e-30)[:, None]
    up = (year["sun_direct_normal_lx"] > 0) & (s[:, 2] > 0)
    return s, up


def test_overhang_over_an_open_site(year):
    scene = lightsolver.Scene()
    scene.add_material("grey", "diffuse", reflectance=0.5)
    plate(scene, "overhang", -5, 5, -1, 0, 2)
    points = np.array([[0, 1.5, 0], [0, 0.5, 0], [0, 3, 0]], float)
    normals = np.tile([0.0, 0.0, 1.0], (3, 1))
    e = lightsolver.direct_sun(scene, points, normals, year["sun_direction"],
                               year["sun_direct_normal_lx"])
    assert e.dtype == np.float32 and e.shape == (len(year["sun_direct_normal_lx"]), 3)
    s, up = lit_hours(year)
    en = year["sun_direct_normal_lx"].astype(float)
    for p, (x, y, _) in enumerate(points):
        with np.errstate(divide="ignore", invalid="ignore"):
            t = 2.0 / s[:, 2]
            xs, ys = x + t * s[:, 0], y + t * s[:, 1]
        under = (ys >= -1) & (ys <= 0) & (np.abs(xs) <= 5)
        near = np.minimum(np.abs(ys + 1), np.abs(ys)) < 1e-4
        expected = np.where(up & ~under, en * s[:, 2], 0.0)
        keep = ~(up & near)
        assert np.allclose(e[keep, p], expected[keep], rtol=1e-5, atol=1e-3)
        assert (e[up & under & ~near, p] == 0).all()
    assert (e[:, 0] > 0).sum() < (e[:, 2] > 0).sum()  # the overhang shades the first point
    # An open site with openings=[] is the same as the scene's (it has no sun and no sky).
    assert np.array_equal(e, lightsolver.direct_sun(
        scene, points, normals, year["sun_direction"], year["sun_direct_normal_lx"], openings=[]))


def fresnel_single(cos_i: float) -> float:
    """Unpolarised transmittance of one clear pane (two interfaces, n 1.52, incoherent)."""
    n = 1.52
    sin_t = math.sqrt(1 - cos_i ** 2) / n
    cos_t = math.sqrt(1 - sin_t ** 2)
    rs = ((cos_i - n * cos_t) / (cos_i + n * cos_t)) ** 2
    rp = ((n * cos_i - cos_t) / (n * cos_i + cos_t)) ** 2
    return 0.5 * ((1 - rs) / (1 + rs) + (1 - rp) / (1 + rp))


def test_glazed_skylight_portal_of_the_scenes_sun(year):
    """A 2 × 2 m skylight portal 1 m above the point (its normal down, into the room): the point
    is sunlit when the ray meets z = 1 within the square, by τv T(θ)/T(0) · frame · maintenance."""
    scene = lightsolver.Scene()
    scene.add_material("grey", "diffuse")
    glazing = {"transmittance": 0.6, "panes": 1, "frame_factor": 0.8, "maintenance_factor": 0.9}
    portal = {"corner": [-1, -1, 1], "edge1": [0, 2, 0], "edge2": [2, 0, 0], "glazing": glazing}
    scene.add_light("sun", "sun", illuminance_lx=1e5, direction=[0, 0, -1], portals=[portal])
    points, normals = np.zeros((1, 3)), np.array([[0.0, 0.0, 1.0]])
    args = (points, normals, year["sun_direction"], year["sun_direct_normal_lx"])
    e = lightsolver.direct_sun(scene, *args)
    assert np.array_equal(e, lightsolver.direct_sun(scene, *args, openings=[portal]))
    s, up = lit_hours(year)
    en = year["sun_direct_normal_lx"].astype(float)
    inside = 0
    for h in np.flatnonzero(up):
        x, y = s[h, 0] / s[h, 2], s[h, 1] / s[h, 2]
        if min(abs(abs(x) - 1), abs(abs(y) - 1)) < 1e-4:
            continue
        if abs(x) < 1 and abs(y) < 1:
            inside += 1
            tau = 0.6 * fresnel_single(s[h, 2]) / fresnel_single(1.0) * 0.8 * 0.9
            assert e[h, 0] == pytest.approx(en[h] * s[h, 2] * tau, rel=1e-5)
        else:
            assert e[h, 0] == 0
    assert inside > 100
    assert (e[~up] == 0).all()
    # Turned over (edge1 × edge2 up, out of the room) the portal passes nothing; two-sided, all.
    over = dict(portal, edge1=[2, 0, 0], edge2=[0, 2, 0])
    assert (lightsolver.direct_sun(scene, *args, openings=[over]) == 0).all()
    assert np.array_equal(e, lightsolver.direct_sun(scene, *args,
                                                    openings=[dict(over, two_sided=True)]))


def test_errors_name_the_field(year):
    scene = lightsolver.Scene()
    pts = np.zeros((2, 3))
    up = np.tile([0.0, 0.0, 1.0], (2, 1))
    d, e = year["sun_direction"], year["sun_direct_normal_lx"]
    with pytest.raises(lightsolver.InputError, match="normals"):
        lightsolver.direct_sun(scene, pts, up[:1], d, e)
    with pytest.raises(lightsolver.InputError, match=r"normals\[1\]"):
        lightsolver.direct_sun(scene, pts, np.array([[0, 0, 1], [0, 0, 2]], float), d, e)
    with pytest.raises(lightsolver.InputError, match="points"):
        lightsolver.direct_sun(scene, np.zeros((2, 2)), up, d, e)
    with pytest.raises(lightsolver.InputError, match="sun_direction"):
        lightsolver.direct_sun(scene, pts, up, d[:-1], e)
    bad = e.copy()
    bad[5] = np.nan
    with pytest.raises(lightsolver.InputError, match=r"sun_direct_normal_lx\[5\]"):
        lightsolver.direct_sun(scene, pts, up, d, bad)
    with pytest.raises(lightsolver.InputError, match=r"openings\[0\]\.glazing\.panes"):
        lightsolver.direct_sun(scene, pts, up, d, e, openings=[
            {"corner": [0, 0, 1], "edge1": [1, 0, 0], "edge2": [0, 1, 0],
             "glazing": {"transmittance": 0.7, "panes": 3}}])
