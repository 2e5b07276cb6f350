#!/usr/bin/python3
"""Writes the sample luminaires of this folder (IES LM-63 and EULUMDAT) from analytic
distributions, so the IES and LDT file of one luminaire hold the same intensities.

Run: /usr/bin/python3 Resources/luminaires/generate.py   (numpy only; output is deterministic)

Each distribution f(d) is a function of the direction d in the luminaire frame (gamma = 0
toward -z, C0 toward +x, C90 toward +y). Its amplitude is set so that the exact integral of f
over the sphere (fine midpoint quadrature, independent of any grid) equals the stated lumens;
the script then checks that the bilinear interpolation of the written grid integrates to the
same lumens within 0.3 %, which is what makes these files "well sampled".
"""
import math
import os

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
CRLF = "\r\n"


def direction(c_deg, g_deg):
    c, g = np.radians(c_deg), np.radians(g_deg)
    return np.sin(g) * np.cos(c), np.sin(g) * np.sin(c), -np.cos(g)


# --- the four distributions (relative; scaled to their lumens below) -----------------------

def downlight(x, y, z):
    """Rotationally symmetric narrow downlight: cos^6(gamma), nothing upward."""
    return np.where(z < 0, (-z) ** 6, 0.0)


def wallwasher(x, y, z):
    """Beam tilted 35 degrees toward C0 (+x), small soft spill, faded to zero over the last
    10 degrees above the horizontal (a visor), nothing upward."""
    ax, az = math.sin(math.radians(35)), -math.cos(math.radians(35))
    beam = np.clip(x * ax + z * az, 0.0, None) ** 8
    visor = np.clip(-z / math.sin(math.radians(10)), 0.0, 1.0)
    return np.where(z < 0, (beam + 0.02 * (-z)) * visor, 0.0)


def batwing(x, y, z):
    """Office panel: batwing peak near gamma 52, wider in C0-C180 than in C90-C270.
    I = cos g (0.25 + 1.8 sin^2 g (1 + 0.3 cos 2C)), smooth at the nadir: sin^2 g cos 2C =
    x^2 - y^2."""
    cos_g = np.clip(-z, 0.0, None)
    return np.where(z < 0, cos_g * (0.25 + 1.8 * (1.3 * x * x + 0.7 * y * y)), 0.0)


def linear_tube(x, y, z):
    """Bare tube along x (I ~ sin of the angle to the tube) on a batten that dims the uplight."""
    return np.sqrt(np.clip(1.0 - x * x, 0.0, None)) * (1.0 - 0.4 * np.clip(z, 0.0, None))


# --- integration ---------------------------------------------------------------------------

def sphere_flux(f, n=1000):
    """Integral of f over the sphere by the midpoint rule in (C, cos gamma): f in cd -> lm."""
    c = (np.arange(2 * n) + 0.5) * 360.0 / (2 * n)
    mu = -1.0 + (np.arange(n) + 0.5) * 2.0 / n  # cos(gamma)
    cc, mm = np.meshgrid(c, mu, indexing="ij")
    g = np.degrees(np.arccos(mm))
    vals = f(*direction(cc, g))
    return vals.sum() * (2 * math.pi / (2 * n)) * (2.0 / n)


def bilinear_flux(c_deg, g_deg, table):
    """Exact integral of the bilinear interpolation of table[c][g] times sin(gamma)."""
    total = 0.0
    for i in range(len(c_deg) - 1):
        dp = math.radians(c_deg[i + 1] - c_deg[i])
        for j in range(len(g_deg) - 1):
            a, d = math.radians(g_deg[j]), math.radians(g_deg[j + 1] - g_deg[j])
            s0 = math.cos(a) - math.cos(a + d)
            u = math.sin(a) * (d * math.sin(d) + math.cos(d) - 1) + math.cos(a) * (
                math.sin(d) - d * math.cos(d))
            w1 = u / d
            w0 = s0 - w1
            lo = 0.5 * (table[i][j] + table[i + 1][j])
            hi = 0.5 * (table[i][j + 1] + table[i + 1][j + 1])
            total += dp * (lo * w0 + hi * w1)
    return total


def full_circle(c_stored, table, symmetry):
    """Unfolds stored planes to 0..360 (only to check the integral here)."""
    if symmetry == "rotational":
        return [0.0, 360.0], [table[0], table[0]]
    rows = dict(zip(c_stored, table))
    if symmetry == "quadrant":
        for c in c_stored:
            rows.setdefault(180 - c, rows[c]), rows.setdefault(180 + c, rows[c])
            rows.setdefault(360 - c, rows[c])
    if symmetry == "bilateral":
        for c in c_stored:
            rows.setdefault(360 - c, rows[c])
    rows.setdefault(360.0, rows[0.0])
    cs = sorted(rows)
    return cs, [rows[c] for c in cs]


# --- writers -------------------------------------------------------------------------------

def wrap(values, fmt, per_line=10):
    out = []
    for k in range(0, len(values), per_line):
        out.append(" ".join(fmt % v for v in values[k:k + per_line]))
    return out


def write_ies(name, lum, c_deg, g_deg, cd):
    year = lum["ies_version"]
    lines = ["IES:LM-63-2019" if year == 2019 else "IESNA:LM-63-2002"]
    for key, value in lum["keywords"]:
        lines.append("[%s] %s" % (key, value))
    lines.append("TILT=NONE")
    mult = lum.get("multiplier", 1.0)
    w, l, h = lum["ies_opening_m"]
    lines.append("%d %g %g %d %d 1 2 %g %g %g" % (
        lum["lamps"], lum["lumens"] / lum["lamps"], mult, len(g_deg), len(c_deg), w, l, h))
    third = 1.00010 if year == 2019 else 1.0
    lines.append("1.0 %.5f %g" % (third, lum["watts"]))
    lines += wrap(g_deg, "%g")
    lines += wrap(c_deg, "%g")
    for row in cd:
        lines += wrap([v / mult for v in row], "%.1f")
    with open(os.path.join(HERE, name), "w", newline="") as f:
        f.write(CRLF.join(lines) + CRLF)


def write_ldt(name, lum, mc, c_all, g_deg, stored_rows, dff):
    lumens = lum["lumens"]
    lines = ["Lighting project", str(lum["ityp"]),
             str(lum["isym"]), str(mc), "%g" % (360.0 / mc), str(len(g_deg)),
             "%g" % (g_deg[1] - g_deg[0]), "LS-SAMPLE", lum["title"], lum["catalog"],
             name, "2025-01-01 generate.py"]
    lines += ["%g" % v for v in lum["ldt_body_mm"]]
    lines += ["%g" % v for v in lum["ldt_area_mm"]]
    lines += ["%.1f" % dff, "100.0", "1.0", "0.0", "1", str(lum["lamps"]), lum["lamp"],
              "%g" % lumens, "3000K", "80", "%g" % lum["watts"]]
    lines += ["0"] * 10  # direct ratios (utilance) are not computed for these samples
    lines += ["%g" % c for c in c_all]
    lines += ["%g" % g for g in g_deg]
    for row in stored_rows:
        lines += ["%.1f" % (v * 1000.0 / lumens) for v in row]
    with open(os.path.join(HERE, name), "w", newline="") as f:
        f.write(CRLF.join(lines) + CRLF)


# --- the luminaires ------------------------------------------------------------------------

LUMINAIRES = [
    dict(stem="downlight", f=downlight, lumens=1500.0, lamps=1, watts=14.0, ies_version=2002,
         title="LS-DL-150 downlight", catalog="LS-DL-150", lamp="LED module 1500 lm",
         symmetry="rotational", ies_c=[0.0], ies_g=np.arange(0, 90.01, 2.5),
         ldt_mc=24, isym=1, ityp=1, ldt_g=np.arange(0, 180.01, 2.5),
         ies_opening_m=(-0.15, -0.15, 0.0), ldt_body_mm=(170, 0, 80),
         ldt_area_mm=(150, 0, 0, 0, 0, 0),
         keywords=[("TEST", "LS-0001 (analytic, not measured)"), ("MANUFAC", "Lighting project"),
                   ("LUMCAT", "LS-DL-150"), ("LUMINAIRE", "Downlight, cos^6 beam"),
                   ("LAMP", "LED module 1500 lm")]),
    dict(stem="wallwasher", f=wallwasher, lumens=2000.0, lamps=1, watts=20.0, ies_version=2002,
         title="LS-WW-20 wall-washer", catalog="LS-WW-20", lamp="LED module 2000 lm",
         symmetry="none", ies_c=np.arange(0, 360.01, 5.0), ies_g=np.arange(0, 90.01, 2.5),
         ldt_mc=72, isym=0, ityp=3, ldt_g=np.arange(0, 180.01, 2.5),
         ies_opening_m=(0.10, 0.20, 0.0), ldt_body_mm=(240, 140, 90),
         ldt_area_mm=(200, 100, 0, 0, 0, 0),
         keywords=[("TEST", "LS-0002 (analytic, not measured)"), ("MANUFAC", "Lighting project"),
                   ("LUMCAT", "LS-WW-20"), ("LUMINAIRE", "Wall-washer, beam 35 deg toward C0"),
                   ("LAMP", "LED module 2000 lm")]),
    dict(stem="batwing_panel", f=batwing, lumens=3600.0, lamps=4, watts=36.0, ies_version=2002,
         multiplier=0.5, title="LS-BW-600 office panel", catalog="LS-BW-600",
         lamp="4 x LED strip 900 lm", symmetry="quadrant", ies_c=np.arange(0, 90.01, 7.5),
         ies_g=np.arange(0, 90.01, 2.5), ldt_mc=48, isym=4, ityp=3,
         ldt_g=np.arange(0, 180.01, 2.5), ies_opening_m=(0.6, 0.6, 0.0),
         ldt_body_mm=(620, 620, 40), ldt_area_mm=(600, 600, 0, 0, 0, 0),
         keywords=[("TEST", "LS-0003 (analytic, not measured)"), ("MANUFAC", "Lighting project"),
                   ("LUMCAT", "LS-BW-600"), ("LUMINAIRE", "Batwing office panel 600 x 600"),
                   ("LAMP", "4 x LED strip 900 lm")]),
    dict(stem="linear_tube", f=linear_tube, lumens=2600.0, lamps=1, watts=24.0, ies_version=2019,
         title="LS-LT-1200 linear tube", catalog="LS-LT-1200", lamp="T8 LED tube 2600 lm",
         symmetry="bilateral", ies_c=np.arange(0, 180.01, 5.0), ies_g=np.arange(0, 180.01, 2.5),
         ldt_mc=72, isym=2, ityp=2, ldt_g=np.arange(0, 180.01, 2.5),
         ies_opening_m=(-0.026, 1.2, -0.026), ldt_body_mm=(1250, 60, 50),
         ldt_area_mm=(1200, 26, 26, 26, 26, 26),
         keywords=[("TEST", "LS-0004 (analytic, not measured)"), ("TESTLAB", "Lighting project"),
                   ("ISSUEDATE", "2025-01-01"), ("MANUFAC", "Lighting project"),
                   ("LUMCAT", "LS-LT-1200"), ("LUMINAIRE", "Batten with bare linear tube"),
                   ("LAMP", "T8 LED tube 2600 lm")]),
]


def table(f, amplitude, c_deg, g_deg):
    cc, gg = np.meshgrid(c_deg, g_deg, indexing="ij")
    return np.round(amplitude * f(*direction(cc, gg)), 1)


def downward_fraction(f):
    return 100.0 * sphere_flux(lambda x, y, z: np.where(z < 0, f(x, y, z), 0.0)) / sphere_flux(f)


def generate(lum):
    f = lum["f"]
    amplitude = lum["lumens"] / sphere_flux(f)
    ies_cd = table(f, amplitude, lum["ies_c"], lum["ies_g"])
    cs, rows = full_circle(list(lum["ies_c"]), list(ies_cd), lum["symmetry"])
    check = bilinear_flux(cs, list(lum["ies_g"]), rows) / lum["lumens"] - 1.0
    assert abs(check) < 0.003, "%s: grid integrates %.3f %% off" % (lum["stem"], 100 * check)
    write_ies(lum["stem"] + ".ies", lum, list(lum["ies_c"]), list(lum["ies_g"]), ies_cd)

    mc = lum["ldt_mc"]
    c_all = [k * 360.0 / mc for k in range(mc)]
    stored = {0: mc, 1: 1, 2: mc // 2 + 1, 4: mc // 4 + 1}[lum["isym"]]
    ldt_cd = table(f, amplitude, c_all[:stored], lum["ldt_g"])
    write_ldt(lum["stem"] + ".ldt", lum, mc, c_all, list(lum["ldt_g"]), ldt_cd,
              downward_fraction(f))
    print("%-14s amplitude %9.2f cd, grid flux error %+.3f %%" % (lum["stem"], amplitude,
                                                                     100 * check))


if __name__ == "__main__":
    for lum in LUMINAIRES:
        generate(lum)
