# SPDX-License-Identifier: LGPL-2.1-or-later
"""Quasi-random vs random photons (docs/BENCHMARKS.md, "Quasi-random photons"): the per-cell
rms relative error of a work-plane grid against photons, `--sampler random` and `--sampler
sobol` (8 replicates) side by side, on

(a) direct light: an isotropic 100 cd point source 2.1 m over a 16 x 16 grid, nothing else in
    the scene; the exact cell means are the inverse-square law integrated over each cell
    (the solid angle of the cell from the source, Van Oosterom & Strackee);
(b) indirect light: the 4 x 4 x 3 m box room of issue 28 (every surface diffuse rho 0.5), lit
    by a 1 x 1 m Lambertian panel at 2.5 m facing the ceiling, so that only reflected light
    reaches the 16 x 16 work-plane grid at 0.8 m; the reference is a long sobol run (32
    replicates of 2^20 photons) whose own
    variance (from its replicates) is subtracted from the mean squared error;
(c) both: the box room of issue 28 as it stands, the 100 cd point source at (2, 2, 2.9) over
    the same grid (direct and reflected light), against a reference as in (b).

Each point is the mean over `SEEDS` seeds of the squared relative error over all cells. Prints
a Markdown table and each sampler's fitted slope of log rms against log photons.

    /usr/bin/python3 Tests/benchmarks/qmc_bench.py build/NativeSolver/cli/lightsolver [CASE]

CASE: direct, indirect or room (default all three).
"""
import json
import math
import os
import subprocess
import sys
import tempfile
from typing import Dict, List, Sequence, Tuple

Vec = Tuple[float, float, float]
SEEDS = 6
CELLS = 16
SOURCE: Vec = (2.0, 2.0, 2.9)
PLANE_Z = 0.8
FLUX_100CD = 400.0 * math.pi  # 100 cd isotropic


def sub(a: Sequence[float], b: Sequence[float]) -> Vec:
    """a - b."""
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def triangle_solid_angle(p: Vec, a: Vec, b: Vec, c: Vec) -> float:
    """Solid angle of triangle abc seen from p (Van Oosterom & Strackee 1983)."""
    r = [sub(a, p), sub(b, p), sub(c, p)]
    n = [math.sqrt(sum(x * x for x in v)) for v in r]
    cross = (r[1][1] * r[2][2] - r[1][2] * r[2][1], r[1][2] * r[2][0] - r[1][0] * r[2][2],
             r[1][0] * r[2][1] - r[1][1] * r[2][0])
    triple = sum(r[0][i] * cross[i] for i in range(3))

    def dot(i: int, j: int) -> float:
        return sum(r[i][k] * r[j][k] for k in range(3))

    den = n[0] * n[1] * n[2] + dot(0, 1) * n[2] + dot(0, 2) * n[1] + dot(1, 2) * n[0]
    return abs(2.0 * math.atan2(triple, den))


def exact_direct_cells() -> List[float]:
    """Each cell's mean illuminance from the 100 cd source: I * solid angle / area."""
    out = []
    h = 4.0 / CELLS
    for iv in range(CELLS):
        for iu in range(CELLS):
            x0, y0 = iu * h, iv * h
            a, b = (x0, y0, PLANE_Z), (x0 + h, y0, PLANE_Z)
            c, d = (x0 + h, y0 + h, PLANE_Z), (x0, y0 + h, PLANE_Z)
            omega = triangle_solid_angle(SOURCE, a, b, c) + triangle_solid_angle(SOURCE, a, c, d)
            out.append(100.0 * omega / (h * h))
    return out


def box_mesh() -> Dict:
    """The 4 x 4 x 3 m room, fronts facing in."""
    v: List[Vec] = []
    t: List[Tuple[int, int, int]] = []
    X, Y, Z = (4.0, 0.0, 0.0), (0.0, 4.0, 0.0), (0.0, 0.0, 3.0)
    for c, e1, e2 in [((0, 0, 0), X, Y), ((0, 0, 3), Y, X), ((0, 0, 0), Z, X),
                      ((0, 4, 0), X, Z), ((0, 0, 0), Y, Z), ((4, 0, 0), Z, Y)]:
        base = len(v)
        v += [c, tuple(c[i] + e1[i] for i in range(3)),
              tuple(c[i] + e1[i] + e2[i] for i in range(3)), tuple(c[i] + e2[i] for i in range(3))]
        t += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    return {"name": "room", "material": "grey", "vertices": v, "triangles": t}


def scene(case: str) -> Dict:
    """Case "direct" (a point source over the grid), "indirect" (the box room, panel up) or
    "room" (the box room, the point source)."""
    grid = {"name": "work plane", "type": "grid", "corner": [0, 0, PLANE_Z], "edge1": [4, 0, 0],
            "edge2": [0, 4, 0], "cells": [CELLS, CELLS]}
    if case == "direct":
        return {"format": "lightsolver.scene/1", "materials": {}, "meshes": [],
                "luminaires": [{"name": "lamp", "type": "point", "position": list(SOURCE),
                                "flux_lm": FLUX_100CD}], "targets": [grid]}
    if case == "room":
        return {"format": "lightsolver.scene/1",
                "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
                "meshes": [box_mesh()], "targets": [grid],
                "luminaires": [{"name": "lamp", "type": "point", "position": list(SOURCE),
                                "flux_lm": FLUX_100CD}]}
    panel = {"name": "uplight", "type": "area", "corner": [1.5, 1.5, 2.5], "edge1": [1, 0, 0],
             "edge2": [0, 1, 0], "flux_lm": 1000.0}  # edge1 x edge2 = +z: toward the ceiling
    return {"format": "lightsolver.scene/1",
            "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
            "meshes": [box_mesh()], "luminaires": [panel], "targets": [grid]}


def run(cli: str, path: str, sampler: str, photons: int, seed: int,
        extra: Sequence[str] = ()) -> Dict:
    """One run's results."""
    out = path + f".{sampler}.{photons}.{seed}.results.json"
    subprocess.run([cli, "run", path, "--backend", "embree", "--sampler", sampler,
                    "--photons", str(photons), "--seed", str(seed), "--out", out, *extra],
                   check=True, stdout=subprocess.DEVNULL)
    with open(out, encoding="utf-8") as f:
        r = json.load(f)
    os.remove(out)
    return r


def cells(r: Dict) -> List[Tuple[float, float, float]]:
    """(lux, ci_low, ci_high) of every cell."""
    return [(c["lux"], c["ci_low_lux"], c["ci_high_lux"]) for c in r["targets"][0]["cells"]]


def rms(cli: str, path: str, sampler: str, photons: int, exact: List[float],
        ref_var: List[float]) -> Tuple[float, float]:
    """(rms relative error over cells and seeds, seconds per run)."""
    sq, seconds = 0.0, 0.0
    for seed in range(1, SEEDS + 1):
        r = run(cli, path, sampler, photons, 100 + seed)
        seconds += r["seconds"]
        for (lux, _, _), e, v in zip(cells(r), exact, ref_var):
            sq += ((lux - e) ** 2 - v) / (e * e)
    return math.sqrt(max(sq, 0.0) / (SEEDS * len(exact))), seconds / SEEDS


def slope(points: List[Tuple[int, float]]) -> float:
    """Least-squares slope of log rms against log photons."""
    xs = [math.log(n) for n, _ in points]
    ys = [math.log(e) for _, e in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main() -> None:
    """Runs both cases and prints the tables."""
    cli = sys.argv[1] if len(sys.argv) > 1 else "build/NativeSolver/cli/lightsolver"
    cases = sys.argv[2:] or ["direct", "indirect", "room"]
    counts = [2 ** k for k in range(15, 24, 2)]
    with tempfile.TemporaryDirectory() as folder:
        for case in cases:
            path = os.path.join(folder, case + ".json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump(scene(case), f)
            if case == "direct":
                exact, ref_var = exact_direct_cells(), [0.0] * CELLS * CELLS
            else:  # a long sobol reference: its mean, and its variance from its interval
                ref = run(cli, path, "sobol", 32 * 2 ** 20, 1, ["--replicates", "32"])
                exact = [c[0] for c in cells(ref)]
                t = 2.0395  # Student-t 0.975 with 31 degrees of freedom
                ref_var = [((c[2] - c[1]) / (2 * t)) ** 2 for c in cells(ref)]
                print(f"reference: {ref['photons']:,} photons in {ref['seconds']:.1f} s")
            print(f"\n({case}) | photons | random rms | sobol rms | random s | sobol s |")
            print("|---|---|---|---|---|")
            table = {"random": [], "sobol": []}
            for n in counts:
                row = {}
                for sampler in ("random", "sobol"):
                    row[sampler] = rms(cli, path, sampler, n, exact, ref_var)
                    table[sampler].append((n, row[sampler][0]))
                print(f"| {n:,} | {100 * row['random'][0]:.3f} % | {100 * row['sobol'][0]:.3f} % | "
                      f"{row['random'][1]:.3f} | {row['sobol'][1]:.3f} |", flush=True)
            print(f"slopes: random {slope(table['random']):.2f}, sobol {slope(table['sobol']):.2f}")


if __name__ == "__main__":
    main()
