"""Value checks of the per-backend goldens (Tests/golden/README.md) against numbers computed
here, independently of the solver, from the formulas in docs/statistics.md and docs/glare.md:
each estimate and interval from its integer tallies, Emin/Emax/U0/Ud intervals from the cells'
tallies, every verdict by the stated rule, UGR by CIE 117's formula from the glare terms, the
area luminaire's luminance and solid angle from the geometry, and the rescaled results from the
traced file's tallies. The solver computes these twice (C++ and GLSL feed the same tallies; the
statistics and glare run in C++ for both backends), so a formula error made the same way on
both sides would pass a comparison of the backends and the goldens' bit-for-bit checks alike,
but not these.

The goldens are checked (not a fresh run): test_golden.py holds a fresh run to them bit for bit.
Tolerances are relative 1e-9: rounding differences of a few ulps pass, any formula error fails.
"""
import json
import math
import subprocess
from statistics import NormalDist

import pytest

from conftest import SOURCE_DIR
from test_golden import BACKEND_GOLDENS, GOLDEN, PER_BACKEND, golden_path

BACKENDS = list(PER_BACKEND["backends"])
#: The factors of the lamps_rescaled golden, read from its command (--dim G=F ...).
_RESCALE_ARGS = PER_BACKEND["commands"]["lamps_rescaled"]
DIMS = {a.split("=")[0]: float(a.split("=")[1])
        for flag, a in zip(_RESCALE_ARGS, _RESCALE_ARGS[1:]) if flag == "--dim"}
REL = 1e-9


def close(a, b, rel=REL):
    """a == b up to rounding (relative, with an absolute floor for values at 0)."""
    return math.isclose(a, b, rel_tol=rel, abs_tol=1e-300)


def load(name, backend):
    return json.loads(golden_path(name, backend).read_text())


def z_two_sided(alpha):
    """The normal quantile of a two-sided level 1 - alpha (one-sided alpha/2 each end)."""
    return NormalDist().inv_cdf(1.0 - alpha / 2.0)


# ---------------------------------------------------------------- estimates from the tallies


def group_estimate(s, q, n, scale, z):
    """(mean, low, high) of one group's bin: docs/statistics.md, "Variance and interval"
    (per-path sigma from S, Q; Wilson's score interval when no path deposited twice)."""
    if n == 0:
        return 0.0, 0.0, 0.0
    p = s / n
    mean = scale * p
    if q == s:  # binomial counts: Wilson
        z2n = z * z / n
        centre = (p + z2n / 2) / (1 + z2n)
        half = z / (1 + z2n) * math.sqrt(p * (1 - p) / n + z2n / (4 * n))
        low = 0.0 if s == 0 else max(0.0, centre - half)
        high = 1.0 if s == n else min(1.0, centre + half)
        return mean, scale * min(low, p), scale * max(high, p)
    var = (n * q - s * s) / (n * n * (n - 1))  # exact integers in Python
    sigma = scale * math.sqrt(var)
    return mean, max(0.0, mean - z * sigma), mean + z * sigma


def combined(parts):
    """The groups' sum and its interval: [E - sqrt(sum d-^2), E + sqrt(sum d+^2)] (docs/
    statistics.md, "The combined interval")."""
    e = sum(m for m, _, _ in parts)
    down = math.sqrt(sum((m - lo) ** 2 for m, lo, _ in parts))
    up = math.sqrt(sum((hi - m) ** 2 for m, _, hi in parts))
    return e, max(0.0, e - down), e + up


class Bins:
    """A results document's groups and tallies, with per-group factors (1: as traced)."""

    def __init__(self, doc, factors=None):
        self.groups = doc["groups"]
        self.factors = {g["name"]: (factors or {}).get(g["name"], 1.0) for g in self.groups}
        self.confidence = doc["confidence"]

    def estimate(self, tallies, area, alpha=None):
        """Combined estimate of one bin; `tallies` maps group -> (S, Q) or (S, Q, direct,
        photon_light): a next-event group's direct part and what its photons tallied."""
        z = z_two_sided(1.0 - self.confidence if alpha is None else alpha)
        parts = []
        for g in self.groups:
            s, q, direct, light = (tuple(tallies[g["name"]]) + (None, None))[:4]
            f = self.factors[g["name"]]
            scale = g["flux_lm"] * f / area
            part = ((0.0, 0.0, 0.0) if light == "none"
                    else group_estimate(s, q, g["photons"], scale, z))
            if light is not None:
                part = with_direct(part, direct or {"lux": 0.0, "variance_lx2": 0.0, "lit": 0},
                                   f, z)
            parts.append(part)
        return combined(parts)


def with_direct(part, direct, factor, z):
    """A photon part plus a direct part (docs/statistics.md, "Next-event estimation"): means
    add, each end's distance in quadrature with z sqrt(Var) plus the direct mean's rounding
    ((lit + 16) eps of it); the direct mean dimmed by f, its variance by f^2."""
    m, lo, hi = part
    lux = direct["lux"] * factor
    half = (z * math.sqrt(direct["variance_lx2"] * factor * factor)
            + (direct["lit"] + 16.0) * 2.0 ** -52 * lux)
    e = m + lux
    return e, max(0.0, e - math.hypot(m - lo, half)), e + math.hypot(hi - m, half)


def target_tallies(t):
    return {g: (c["sum"], c["sum_sq"], c.get("direct"), c.get("photon_light"))
            for g, c in t["contributions"].items()}


def cell_tallies(t, i):
    return {g: (c["cells"][i]["sum"], c["cells"][i]["sum_sq"], c["cells"][i].get("direct"),
                c.get("photon_light"))
            for g, c in t["contributions"].items()}


def cell_area(t):
    nu, nv = t["cells_uv"]
    return t["area_m2"] / (nu * nv)


@pytest.mark.parametrize("backend", BACKENDS)
def test_estimates_and_intervals_follow_from_the_tallies(backend):
    doc = load("lamps", backend)
    bins = Bins(doc)
    assert sum(g["photons"] for g in doc["groups"]) == doc["photons"]
    for t in doc["targets"]:
        e = bins.estimate(target_tallies(t), t["area_m2"])
        got = (t["mean_lux"], t["ci_low_lux"], t["ci_high_lux"])
        assert all(map(close, got, e)), (t["name"], got, e)
        assert t["hits"] == sum(c["sum"] + c.get("direct", {}).get("lit", 0)
                                for c in t["contributions"].values())
        for g, part in t["contributions"].items():
            one = Bins({**doc, "groups": [x for x in doc["groups"] if x["name"] == g]})
            m, lo, hi = one.estimate({g: target_tallies(t)[g]}, t["area_m2"])
            assert all(map(close, (part["illuminance_lux"], part["ci_low_lux"],
                                   part["ci_high_lux"]), (m, lo, hi))), (t["name"], g)
        for i, cell in enumerate(t.get("cells", [])):
            e = bins.estimate(cell_tallies(t, i), cell_area(t))
            assert all(map(close, (cell["lux"], cell["ci_low_lux"], cell["ci_high_lux"]), e))
        if t["type"] in ("observer", "observer_grid"):  # L_b = E / pi
            assert close(t["background_luminance_cd_m2"], t["mean_lux"] / math.pi)
            assert close(t["background_ci_low_cd_m2"], t["ci_low_lux"] / math.pi)
            assert close(t["background_ci_high_cd_m2"], t["ci_high_lux"] / math.pi)


# ---------------------------------------------------------------- Emin, Emax, U0, Ud


def grid_statistics(t, bins):
    """Emin, Emax, U0 and Ud with their intervals by docs/statistics.md, "Emin over noisy
    cells": each end of Emin/Emax from one cell at one-sided alpha/2 or from all m cells at
    alpha/(2m) (Bonferroni); the ratios' ends from bounds at alpha/4, Em at two-sided alpha/2;
    cut at 1, x/0 read as 1 and 0/0 as 0; every interval holding its estimate."""
    alpha = 1.0 - bins.confidence
    m = len(t["cells"])
    area = cell_area(t)

    def cells_at(a):
        return [bins.estimate(cell_tallies(t, i), area, a) for i in range(m)]

    def bounds(tail):
        one, all_ = cells_at(2 * tail), cells_at(2 * tail / m)
        return (min(c[1] for c in one), min(c[2] for c in all_),
                max(c[1] for c in all_), max(c[2] for c in one))

    lux = [c["lux"] for c in t["cells"]]
    emin, emax, em = min(lux), max(lux), t["mean_lux"]
    b = bounds(alpha / 2)
    q = bounds(alpha / 4)
    qmin = (min(q[0], emin), max(q[1], emin))
    qmax = (min(q[2], emax), max(q[3], emax))
    _, em_lo, em_hi = bins.estimate(target_tallies(t), t["area_m2"], alpha / 2)
    em_lo, em_hi = min(em_lo, em), max(em_hi, em)

    def ratio(a, b_, value):
        low = a[0] / b_[1] if b_[1] > 0 else 0.0
        high = min(1.0, a[1] / b_[0]) if b_[0] > 0 else 1.0
        return min(low, value), max(high, value)

    u0 = emin / em if em > 0 else 0.0
    ud = emin / emax if emax > 0 else 0.0
    u0_lo, u0_hi = ratio(qmin, (em_lo, em_hi), u0)
    ud_lo, ud_hi = ratio(qmin, qmax, ud)
    return {"min_lux": emin, "max_lux": emax, "uniformity": u0, "ud": ud,
            "min_ci_low_lux": min(b[0], emin), "min_ci_high_lux": max(b[1], emin),
            "max_ci_low_lux": min(b[2], emax), "max_ci_high_lux": max(b[3], emax),
            "uniformity_ci_low": u0_lo, "uniformity_ci_high": u0_hi,
            "ud_ci_low": ud_lo, "ud_ci_high": ud_hi}


@pytest.mark.parametrize("name,backend", [(n, b) for n, b in BACKEND_GOLDENS
                                          if n in ("lamps", "lamps_rescaled")])
def test_emin_u0_and_ud_intervals_follow_from_the_cells(name, backend):
    doc = load(name, backend)
    bins = Bins(doc)  # a rescaled file's groups carry their dimmed fluxes
    grids = [t for t in doc["targets"] if t["type"] == "grid"]
    assert len(grids) == 2
    for t in grids:
        expected = grid_statistics(t, bins)
        for key, value in expected.items():
            assert close(t[key], value), (name, t["name"], key, t[key], value)
        # Sanity of the method itself: simultaneous intervals are wider than the naive ones.
        assert t["min_ci_high_lux"] >= min(c["ci_high_lux"] for c in t["cells"])


# ---------------------------------------------------------------- verdicts


STATISTIC = {"em": ("mean_lux", "ci_low_lux", "ci_high_lux"),
             "u0": ("uniformity", "uniformity_ci_low", "uniformity_ci_high"),
             "emin": ("min_lux", "min_ci_low_lux", "min_ci_high_lux"),
             "ud": ("ud", "ud_ci_low", "ud_ci_high"),
             "ugr": ("ugr", "ugr_ci_low", "ugr_ci_high")}


def rule(relation, low, high, required):
    """docs/statistics.md "Verdicts" (>=) and docs/glare.md (<=, UGR)."""
    if relation == ">=":
        return "pass" if low >= required else "fail" if high < required else "undecided"
    assert relation == "<="
    if high is not None and high <= required:
        return "pass"
    return "fail" if low > required else "undecided"


def overall(verdicts):
    return ("fail" if "fail" in verdicts else "undecided" if "undecided" in verdicts
            else "pass")


@pytest.mark.parametrize("name,backend", BACKEND_GOLDENS)
def test_every_verdict_follows_the_rule(name, backend):
    doc = load(name, backend)
    judged = []
    for t in doc["targets"]:
        if "verdicts" not in t:
            continue
        for kind, v in t["verdicts"].items():
            value, low, high = (t[k] for k in STATISTIC[kind])
            assert (v["value"], v["ci_low"], v["ci_high"]) == (value, low, high), (t["name"], kind)
            assert v["relation"] == ("<=" if kind == "ugr" else ">=")
            req_key = {"em": "em_lux", "emin": "emin_lux", "ugr": "ugr_max"}.get(kind, kind)
            assert v["required"] == t["requirements"][req_key]
            assert v["verdict"] == rule(v["relation"], low, high, v["required"]), (t["name"], kind)
            if v["verdict"] == "undecided":
                # N (w/d)^2 (at least N) with w the half-width facing the bound, d the
                # distance to it.
                d = abs(value - v["required"])
                assert d > 0  # on the bound no run decides it (photons null)
                w = value - low if value > v["required"] else high - value
                need = max(doc["photons"] * (w / d) ** 2, doc["photons"])
                assert v["to_decide"]["photons"] == math.ceil(need)
            else:
                assert "to_decide" not in v
        assert t["verdict"] == overall([v["verdict"] for v in t["verdicts"].values()])
        judged.append(t["verdict"])
    if judged:
        assert doc["verdict"] == overall(judged)


def run_materials_with(cli, tmp_path, requirements):
    """The materials golden scene on Embree with requirements on its 'under block' grid."""
    scene = json.loads((GOLDEN / "scenes" / "materials.json").read_text())
    scene["targets"][0]["requirements"] = requirements
    path, out = tmp_path / "scene.json", tmp_path / "out.json"
    path.write_text(json.dumps(scene))  # repr of a float: the bound exactly
    r = subprocess.run([cli, "run", str(path), "--backend", "embree", "--quiet", "--out",
                        str(out)], capture_output=True, text=True, timeout=120, cwd=SOURCE_DIR)
    assert r.returncode == 0, r.stderr
    return json.loads(out.read_text())["targets"][0]


def test_a_bound_exactly_at_an_interval_end(cli, tmp_path):
    """Requirements do not change what is traced, so bounds taken from a first run's interval
    ends are hit exactly: lower end on the bound passes (the allowed set holds r), upper end
    on it is undecided (not a fail), one ulp above the upper end fails."""
    t = run_materials_with(cli, tmp_path, {"u0": 0.01})  # a grid judged has its U0 interval
    em_lo, em_hi = t["ci_low_lux"], t["ci_high_lux"]
    u0_lo, u0_hi = t["uniformity_ci_low"], t["uniformity_ci_high"]
    first = run_materials_with(cli, tmp_path, {"em_lux": em_lo, "u0": u0_hi})
    assert first["ci_low_lux"] == em_lo and first["uniformity_ci_high"] == u0_hi
    assert first["verdicts"]["em"]["verdict"] == "pass"
    assert first["verdicts"]["u0"]["verdict"] == "undecided"
    above = run_materials_with(cli, tmp_path, {"em_lux": math.nextafter(em_hi, math.inf),
                                               "u0": math.nextafter(u0_lo, 0)})
    assert above["verdicts"]["em"]["verdict"] == "fail"
    assert above["verdicts"]["u0"]["verdict"] == "pass"


# ---------------------------------------------------------------- UGR


def ugr(lb, terms_sum):
    """CIE 117: UGR = 8 log10(0.25 / L_b * sum L^2 omega / p^2); None at L_b = 0."""
    return 8.0 * math.log10(0.25 / lb * terms_sum) if lb > 0 else None


@pytest.mark.parametrize("name,backend", [(n, b) for n, b in BACKEND_GOLDENS
                                          if n in ("lamps", "lamps_rescaled")])
def test_observer_ugr_by_the_cie_formula(name, backend):
    doc = load(name, backend)
    (t,) = [t for t in doc["targets"] if t["type"] == "observer"]
    counted = [lum for lum in t["luminaires"] if lum["counted"]]
    assert counted and any(not lum["counted"] for lum in t["luminaires"])
    terms = [lum["luminance_cd_m2"] ** 2 * lum["solid_angle_sr"] / lum["position_index"] ** 2
             for lum in counted]
    lb, lb_lo, lb_hi = (t[k] for k in ("background_luminance_cd_m2", "background_ci_low_cd_m2",
                                       "background_ci_high_cd_m2"))
    assert close(t["ugr"], ugr(lb, sum(terms)))
    assert close(t["ugr_ci_low"], ugr(lb_hi, sum(terms)))  # UGR falls as L_b rises
    assert close(t["ugr_ci_high"], ugr(lb_lo, sum(terms)))
    for lum, term in zip(counted, terms):
        assert close(lum["ugr_alone"], ugr(lb, term))


def point_terms(og, k):
    """Each counted luminaire's (L, omega, p) at observer-grid point k, with its name."""
    terms = og["glare_terms"]
    flat = terms["terms"][k]
    names = [n for n, s in zip(terms["luminaires"], terms["status"][k]) if s == "c"]
    assert len(flat) == 3 * len(names)
    return {n: tuple(flat[3 * i:3 * i + 3]) for i, n in enumerate(names)}


@pytest.mark.parametrize("name,backend", [(n, b) for n, b in BACKEND_GOLDENS
                                          if n in ("lamps", "lamps_rescaled")])
def test_observer_grid_ugr_and_its_maximum(name, backend):
    doc = load(name, backend)
    bins = Bins(doc)
    (t,) = [t for t in doc["targets"] if t["type"] == "observer_grid"]
    og = t["observer_grid"]
    ndir = len(og["view_directions"])
    alpha = 1.0 - doc["confidence"]
    points, glare = [], []
    for k in range(len(og["positions"]) * ndir):
        i, j = divmod(k, ndir)
        tallies = {g: tuple(c["points"][k]) + (None, c.get("photon_light"))
                   for g, c in t["contributions"].items()}
        lb = [v / math.pi for v in bins.estimate(tallies, t["area_m2"])]
        assert all(close(og[key][i][j], v) for key, v in zip(
            ("background_luminance_cd_m2", "background_ci_low_cd_m2",
             "background_ci_high_cd_m2"), lb))
        total = sum(l_ * l_ * w / p / p for l_, w, p in point_terms(og, k).values())
        if total > 0:
            assert close(og["ugr"][i][j], ugr(lb[0], total))
            assert close(og["ugr_ci_low"][i][j], ugr(lb[2], total))
            assert close(og["ugr_ci_high"][i][j], ugr(lb[1], total))
            glare.append(k)
        else:
            assert og["ugr"][i][j] is None
        points.append((tallies, total))
    assert 0 < len(glare) < len(points)  # some eyes see no rated luminaire
    # The maximum: the largest estimate; upper end the points' own upper ends; lower end each
    # point's L_b upper bound at one-sided alpha / (2m), m the points with glare.
    best = max(glare, key=lambda k: og["ugr"][k // ndir][k % ndir])
    assert og["max_at"] == {"position": best // ndir, "direction": best % ndir}
    assert t["ugr"] == og["ugr"][best // ndir][best % ndir]
    assert close(t["ugr_ci_high"], max(og["ugr_ci_high"][k // ndir][k % ndir] for k in glare))
    lows = []
    for k in glare:
        tallies, total = points[k]
        lb_hi = bins.estimate(tallies, t["area_m2"], alpha / len(glare))[2] / math.pi
        lows.append(ugr(lb_hi, total))
    assert close(t["ugr_ci_low"], min(max(lows), t["ugr"]))
    # Wider below than the arg-max point's own interval (docs/glare.md, "Observer grids").
    assert t["ugr_ci_low"] < og["ugr_ci_low"][best // ndir][best % ndir]


def test_area_luminaire_glare_terms_from_the_geometry():
    """The panel (a Lambertian parallelogram): L = flux / (pi A) toward every eye in front,
    omega = A cos(theta) / r^2 (docs/glare.md), at every observer-grid point where it counts."""
    scene = json.loads((GOLDEN / "scenes" / "lamps.json").read_text())
    (panel,) = [lum for lum in scene["luminaires"] if lum["name"] == "panel"]
    e1, e2 = panel["edge1"], panel["edge2"]
    n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
         e1[0] * e2[1] - e1[1] * e2[0]]
    area = math.sqrt(sum(x * x for x in n))
    centre = [panel["corner"][i] + (e1[i] + e2[i]) / 2 for i in range(3)]
    for backend in BACKENDS:
        for name, factor in (("lamps", 1.0), ("lamps_rescaled", DIMS.get(panel["group"], 1.0))):
            og = [t for t in load(name, backend)["targets"]
                  if t["type"] == "observer_grid"][0]["observer_grid"]
            ndir, seen = len(og["view_directions"]), 0
            for k, status in enumerate(og["glare_terms"]["status"]):
                if status[0] != "c":
                    continue
                eye = og["positions"][k // ndir]
                d = [centre[i] - eye[i] for i in range(3)]
                r = math.sqrt(sum(x * x for x in d))
                cos = -sum(d[i] * n[i] for i in range(3)) / (r * area)
                lum, omega, _ = point_terms(og, k)["panel"]
                assert close(lum, factor * panel["flux_lm"] / (math.pi * area))
                assert close(omega, area * cos / r ** 2)
                seen += 1
            assert seen >= 2


# ---------------------------------------------------------------- emitted flux


def tilt_table(path):
    """(angles, factors) of an IES file's TILT=INCLUDE table, read here."""
    lines = path.read_text().splitlines()
    i = next(k for k, line in enumerate(lines) if line.startswith("TILT=INCLUDE"))
    return ([float(x) for x in lines[i + 3].split()], [float(x) for x in lines[i + 4].split()])


def interpolate(x, xs, ys):
    k = next(k for k in range(1, len(xs)) if x <= xs[k])
    return ys[k - 1] + (ys[k] - ys[k - 1]) * (x - xs[k - 1]) / (xs[k] - xs[k - 1])


def emitted_flux(lum, base):
    """A luminaire's emitted flux by docs/scene-format.md: flux_lm; a directional beam's
    E * A * |n.d|; a photometric file's integrated flux times flux_lm / lamp lumens (when
    given) times its TILT factor at the aim's angle from straight down (type C)."""
    import lightsolver  # noqa: PLC0415 (the build's module; conftest puts it on the path)

    if lum["type"] in ("point", "spot", "area"):
        return lum["flux_lm"]
    if lum["type"] == "directional":
        e1, e2, d = lum["edge1"], lum["edge2"], lum["direction"]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
             e1[0] * e2[1] - e1[1] * e2[0]]
        return lum["illuminance_lx"] * abs(sum(a * b for a, b in zip(n, d))) / math.hypot(*d)
    path = base / lum["file"]
    info = lightsolver.photometry_summary(str(path))
    flux = info["integrated_lumens_lm"]
    if "flux_lm" in lum:
        flux *= lum["flux_lm"] / info["lamp_lumens_lm"]
    if "TILT=INCLUDE" in path.read_text():
        aim = lum.get("aim", [0, 0, -1])
        tilt = math.degrees(math.acos(-aim[2] / math.hypot(*aim)))
        flux *= interpolate(tilt, *tilt_table(path))
    return flux


@pytest.mark.parametrize("backend", BACKENDS)
def test_group_fluxes_are_the_luminaires_emitted_flux_with_tilt(backend):
    scene = json.loads((GOLDEN / "scenes" / "lamps.json").read_text())
    doc = load("lamps", backend)
    expected = {}
    for lum in scene["luminaires"]:
        expected[lum["group"]] = expected.get(lum["group"], 0.0) + emitted_flux(
            lum, GOLDEN / "scenes")
    assert {g["name"]: g["flux_lm"] for g in doc["groups"]} == pytest.approx(expected, rel=1e-12)
    assert close(doc["total_flux_lm"], sum(expected.values()))
    tilted = [lum for lum in scene["luminaires"] if "tilt" in lum.get("file", "")]
    assert tilted and all(lum.get("aim") for lum in tilted)  # aimed off straight down


# ---------------------------------------------------------------- rescale


@pytest.mark.parametrize("backend", BACKENDS)
def test_rescaled_results_follow_from_the_traced_tallies(backend):
    """Each group's part times its factor, the interval combined from the dimmed parts
    (docs/statistics.md, "Groups"), computed from the traced file's tallies."""
    traced, rescaled = load("lamps", backend), load("lamps_rescaled", backend)
    assert set(DIMS) <= {g["name"] for g in traced["groups"]} and 0.0 in DIMS.values()
    assert rescaled["rescaled"] == {g["name"]: DIMS.get(g["name"], 1.0) for g in traced["groups"]}
    for before, after in zip(traced["groups"], rescaled["groups"]):
        assert close(after["flux_lm"], before["flux_lm"] * DIMS.get(before["name"], 1.0))
        assert after["photons"] == before["photons"]
    assert close(rescaled["total_flux_lm"], sum(g["flux_lm"] for g in rescaled["groups"]))
    bins = Bins(traced, DIMS)
    for t0, t1 in zip(traced["targets"], rescaled["targets"]):
        e = bins.estimate(target_tallies(t0), t0["area_m2"])
        got = (t1["mean_lux"], t1["ci_low_lux"], t1["ci_high_lux"])
        assert all(map(close, got, e)), (t0["name"], got, e)
        for i, cell in enumerate(t1.get("cells", [])):
            e = bins.estimate(cell_tallies(t0, i), cell_area(t0))
            assert all(map(close, (cell["lux"], cell["ci_low_lux"], cell["ci_high_lux"]), e))
        for g, part in t1["contributions"].items():
            f = DIMS.get(g, 1.0)
            assert close(part["illuminance_lux"], f * t0["contributions"][g]["illuminance_lux"])
            assert part["sum"] == t0["contributions"][g]["sum"]
    # Observer: each luminaire's L times its group's factor, the rest unchanged; a luminaire
    # dimmed to 0 no longer counts.
    group_of = {name: g["name"] for g in traced["groups"] for name in g["luminaires"]}
    o0, o1 = ([t for t in d["targets"] if t["type"] == "observer"][0] for d in (traced, rescaled))
    for a, b in zip(o0["luminaires"], o1["luminaires"]):
        f = DIMS.get(group_of[a["name"]], 1.0)
        if a["counted"] and f > 0:
            assert close(b["luminance_cd_m2"], f * a["luminance_cd_m2"])
            assert (b["solid_angle_sr"], b["position_index"]) == (a["solid_angle_sr"],
                                                                  a["position_index"])
        else:
            assert not b["counted"]
