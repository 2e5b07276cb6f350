# SPDX-License-Identifier: LGPL-2.1-or-later
"""Time to accuracy (issue 28, docs/BENCHMARKS.md "Time to accuracy"): the wall time of
`lightsolver run`, process start to results written, that a configuration needs for a work-plane
grid's per-cell rms relative error of 4.5 %, 2 %, 1 %, 0.7 % and 0.5 % against a long reference.

    /usr/bin/python3 Tests/benchmarks/time_to_accuracy.py [--cli PATH] [--scene box|office|FILE]
        [--config "NAME:EXTRA FLAGS"]... [--targets 0.02,0.01] [--seeds 3] [--repeats 3]

Per scene, a reference run (`--reference-photons`, `--reference-flags`, default none; cached
under `--cache`, build/time_to_accuracy/, by the scene's bytes, the photons, the flags and the
CLI's modification time) gives E_ref per cell and its own per-cell standard error. Per
configuration (its extra CLI flags, e.g. `--config "off:--next-event off"` or, for the connected
reflected light, `--config "connected:--next-event on --connect-reflections on"`: docs/BENCHMARKS.md
"Connected reflected light at grids"), photon counts double
from `--start` until the error is at or below each target, then `--bisect` geometric bisections
narrow the count. The error at N photons
is, over `--seeds` seeds (1, 2, 3, ...), e(N) = sqrt(mean over seeds and cells of
((E - E_ref) / E_ref)^2 - mean over cells of (s_ref / E_ref)^2): the reference's own variance,
independent of the run's, is taken out (it is printed beside). The time at N is the median of the
seeds' wall times (each a whole process: start-up, reading, tracing, writing), beside the median
CPU time of the process (user + system, every thread: what a loaded machine distorts least).

The errors do not depend on the machine's load (fixed seeds), the times do: once every
configuration's photon counts are found, `--repeats` rounds time them again, interleaved (each
round runs every target's count of every configuration, the configurations' order rotating from
round to round), and each cell reports the minimum over the rounds of the seeds' median; the
load average (1 min) at each round's start is printed. Prints a Markdown table (cells: wall /
CPU (photons)) and the time ratios (wall / CPU) against the first configuration; LIGHTSOLVER_CLI or
--cli names the CLI (default build/NativeSolver/cli/lightsolver).
"""
import argparse
import hashlib
import json
import math
import os
import resource
import shlex
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CACHE = ROOT / "build" / "time_to_accuracy"
TARGETS = (0.045, 0.02, 0.01, 0.007, 0.005)
Z95 = 1.959963984540054  # the results' intervals are 95 % two-sided (checked below)


def box_room(folder: Path) -> Path:
    """The issue's box room: a closed 4 x 4 x 3 m box, every face diffuse rho 0.5 facing inward,
    an isotropic 100 cd point source at (2, 2, 2.9) (4 pi 100 lm), a 16 x 16 grid at 0.8 m."""
    lx, ly, h = 4.0, 4.0, 3.0

    def quad(c, e1, e2):  # front = e1 x e2, pointing into the box
        return [c, [c[i] + e1[i] for i in range(3)], [c[i] + e1[i] + e2[i] for i in range(3)],
                [c[i] + e2[i] for i in range(3)]]

    faces = [quad([0, 0, 0], [0, ly, 0], [lx, 0, 0]), quad([0, 0, h], [lx, 0, 0], [0, ly, 0]),
             quad([0, 0, 0], [lx, 0, 0], [0, 0, h]), quad([0, ly, 0], [0, 0, h], [lx, 0, 0]),
             quad([0, 0, 0], [0, 0, h], [0, ly, 0]), quad([lx, 0, 0], [0, ly, 0], [0, 0, h])]
    verts, tris = [], []
    for f in faces:
        b = len(verts)
        verts += f
        tris += [[b, b + 1, b + 2], [b, b + 2, b + 3]]
    scene = {"format": "lightsolver.scene/1",
             "metadata": {"description": "issue 28 box room (time_to_accuracy.py)"},
             "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
             "meshes": [{"name": "box", "material": "grey", "vertices": verts, "triangles": tris}],
             "luminaires": [{"name": "lamp", "type": "point", "flux_lm": 4 * math.pi * 100,
                             "position": [2.0, 2.0, 2.9]}],
             "targets": [{"name": "work plane", "type": "grid", "corner": [0, 0, 0.8],
                          "edge1": [lx, 0, 0], "edge2": [0, ly, 0], "cells": [16, 16]}]}
    path = folder / "box_room.scene.json"
    path.write_text(json.dumps(scene))
    return path


def en12464_cells(length_m: float) -> int:
    """EN 12464-1's grid: cell size p = 0.2 * 5^log10(d), n = ceil(d / p)."""
    return math.ceil(length_m / (0.2 * 5 ** math.log10(length_m)))


def office(folder: Path) -> Path:
    """The furnished room of Table II (Examples/optimization/conference: 66 k triangles, chairs
    and a table, two 3000 lm ceiling panels, all diffuse) without its search block and with a
    work-plane grid at 0.8 m over the floor, 0.5 m from the walls, cells as EN 12464-1 sizes
    them (Examples/room/make_room.py)."""
    src = ROOT / "Examples/optimization/conference/conference.json"
    scene = json.loads(src.read_text())
    scene.pop("optimization", None)
    for m in scene["meshes"]:  # the PLY files stay where they are
        if "file" in m:
            m["file"] = str(src.parent / m["file"])
    xs, ys = [], []
    for m in scene["meshes"]:
        for v in m.get("vertices", []):
            xs.append(v[0])
            ys.append(v[1])
    x0, x1, y0, y1 = min(xs) + 0.5, max(xs) - 0.5, min(ys) + 0.5, max(ys) - 0.5
    scene["targets"] = [{"name": "work plane", "type": "grid", "corner": [x0, y0, 0.8],
                         "edge1": [x1 - x0, 0, 0], "edge2": [0, y1 - y0, 0],
                         "cells": [en12464_cells(x1 - x0), en12464_cells(y1 - y0)]}]
    path = folder / "office.scene.json"
    path.write_text(json.dumps(scene))
    return path


def run(cli: str, scene: Path, photons: int, seed: int, flags: list, out: Path) -> tuple:
    """One `lightsolver run` process: its wall and CPU seconds (user + system, all its threads;
    start to results written) and the first grid's per-cell (lux, 95 % half-width)."""
    cmd = [cli, "run", str(scene), "--photons", str(photons), "--seed", str(seed), "--out",
           str(out), "-q"] + flags
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if done.returncode != 0:
        sys.exit(f"time_to_accuracy: {shlex.join(cmd)} failed:\n{done.stderr}")
    results = json.loads(out.read_text())
    if abs(results["confidence"] - 0.95) > 1e-9:
        sys.exit(f"time_to_accuracy: {scene} asks for confidence {results['confidence']}")
    grid = next(t for t in results["targets"] if t["type"] == "grid")
    cells = [(c["lux"], 0.5 * (c["ci_high_lux"] - c["ci_low_lux"])) for c in grid["cells"]]
    return (wall, cpu), cells


def reference(cli: str, scene: Path, photons: int, flags: list, cache: Path) -> list:
    """The reference's cells (lux, standard error), from the cache when the scene, photons, flags
    and CLI are the same; else one run with seed 1000003, written to the cache atomically."""
    key = hashlib.sha256(scene.read_bytes() + f"{photons} {flags} {os.stat(cli).st_mtime_ns}"
                         .encode()).hexdigest()[:16]
    path = cache / f"{scene.stem}-{photons:.0e}-{key}.json"
    if path.exists():
        return json.loads(path.read_text())["cells"]
    cache.mkdir(parents=True, exist_ok=True)
    print(f"reference: {scene.name}, {photons:.1e} photons ...", file=sys.stderr, flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        (wall, cpu), cells = run(cli, scene, photons, 1000003, flags, Path(tmp) / "ref.json")
    cells = [(e, hw / Z95) for e, hw in cells]
    part = path.with_suffix(".part")
    part.write_text(json.dumps({"photons": photons, "seconds": wall, "cpu_seconds": cpu,
                                "cells": cells}))
    part.replace(path)
    return cells


class Search:
    """Errors and times of one configuration at the photon counts it was run with. The errors
    (fixed seeds: the same for the same scene, flags, seeds, reference and CLI) are kept in
    `cache`, so a second invocation only times the runs again (`--repeats`)."""

    def __init__(self, cli, scene, flags, ref, seeds, folder, cache: Path):
        self.cli, self.scene, self.flags, self.ref = cli, scene, flags, ref
        self.seeds, self.folder, self.at = seeds, folder, {}
        lit = [(e, s) for e, s in ref if e > 0]
        self.ref_var = sum((s / e) ** 2 for e, s in lit) / len(lit)
        key = hashlib.sha256(scene.read_bytes() + json.dumps(
            [flags, seeds, ref, os.stat(cli).st_mtime_ns]).encode()).hexdigest()[:16]
        self.cache = cache / f"errors-{scene.stem}-{key}.json"
        if self.cache.exists():
            self.at = {int(n): tuple(v) for n, v in json.loads(self.cache.read_text()).items()}

    def keep(self) -> None:
        """Writes the errors found so far to the cache (atomically)."""
        self.cache.parent.mkdir(parents=True, exist_ok=True)
        part = self.cache.with_suffix(".part")
        part.write_text(json.dumps({str(n): v for n, v in self.at.items()}))
        part.replace(self.cache)

    def error(self, photons: int) -> float:
        """e(N) as in the module's docstring (NaN-free: a negative difference gives 0)."""
        if photons not in self.at:
            sq, walls, cpus = [], [], []
            for seed in range(1, self.seeds + 1):
                (wall, cpu), cells = run(self.cli, self.scene, photons, seed, self.flags,
                                         self.folder / "run.json")
                walls.append(wall)
                cpus.append(cpu)
                sq += [((e - r) / r) ** 2 for (e, _), (r, _) in zip(cells, self.ref) if r > 0]
            mse = sum(sq) / len(sq) - self.ref_var
            self.at[photons] = (math.sqrt(max(mse, 0.0)), statistics.median(walls),
                                statistics.median(cpus))
            self.keep()
            print(f"  {self.scene.stem} {self.flags}: {photons:.3g} photons: error "
                  f"{100 * self.at[photons][0]:.3f} %, {self.at[photons][1]:.3f} s wall, "
                  f"{self.at[photons][2]:.3f} s CPU", file=sys.stderr, flush=True)
        return self.at[photons][0]

    def photons_for(self, target: float, start: int, steps: int, cap: int) -> int:
        """The smallest count found (doubling, then geometric bisection) with e(N) <= target."""
        lo, hi = None, start
        while self.error(hi) > target:
            lo, hi = hi, hi * 2
            if hi > cap:
                return 0
        if lo is None:  # the start already meets it: halve down first
            while hi > 1000 and self.error(hi // 2) <= target:
                hi //= 2
            lo = hi // 2
        for _ in range(steps):
            mid = int(round(math.sqrt(lo * hi) / 64)) * 64  # a multiple of 64: sobol splits evenly
            if mid in (lo, hi):
                break
            if self.error(mid) <= target:
                hi = mid
            else:
                lo = mid
        return hi


def timed(search: Search, photons: int) -> tuple:
    """The seeds' median wall and CPU seconds of `search`'s configuration at `photons`."""
    walls, cpus = [], []
    for seed in range(1, search.seeds + 1):
        (wall, cpu), _ = run(search.cli, search.scene, photons, seed, search.flags,
                             search.folder / "run.json")
        walls.append(wall)
        cpus.append(cpu)
    return statistics.median(walls), statistics.median(cpus)


def retime(searches: list, counts: list, repeats: int) -> list:
    """Interleaved timing rounds (module docstring): per configuration and target, the minimum
    over the rounds of (median wall, median CPU); the search's own time where `repeats` is 0.
    `counts[c][t]` is configuration c's photon count at target t (0: not reached)."""
    best = [[search.at[n][1:] if n else None for n in row] for search, row in zip(searches, counts)]
    for k in range(repeats):
        load = os.getloadavg()[0]
        print(f"timing round {k + 1}/{repeats}: load average {load:.2f}", file=sys.stderr,
              flush=True)
        order = list(range(len(searches)))
        order = order[k % len(order):] + order[:k % len(order)]
        for t in range(len(counts[0])):
            for c in order:
                n = counts[c][t]
                if not n:
                    continue
                wall, cpu = timed(searches[c], n)
                old = best[c][t] if k > 0 else None
                best[c][t] = (min(wall, old[0]), min(cpu, old[1])) if old else (wall, cpu)
    return best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default_cli = str(ROOT / "build/NativeSolver/cli/lightsolver")
    ap.add_argument("--cli", default=os.environ.get("LIGHTSOLVER_CLI", default_cli))
    ap.add_argument("--scene", action="append", help="box, office or a scene file (repeatable)")
    ap.add_argument("--config", action="append",
                    help='"NAME:EXTRA FLAGS" (repeatable; default "today:" = no extra flags)')
    ap.add_argument("--targets", default=",".join(str(t) for t in TARGETS))
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--start", type=int, default=20_000)
    ap.add_argument("--bisect", type=int, default=3)
    ap.add_argument("--repeats", type=int, default=3,
                    help="interleaved timing rounds after the search (0: the search's times)")
    ap.add_argument("--cap", type=float, default=2e9, help="give up above this photon count")
    ap.add_argument("--reference-photons", type=float, default=2e8)
    ap.add_argument("--reference-flags", default="", help="extra CLI flags of the reference")
    ap.add_argument("--cache", type=Path, default=CACHE, help=f"references' folder ({CACHE})")
    a = ap.parse_args()
    targets = sorted((float(t) for t in a.targets.split(",")), reverse=True)
    configs = [c.split(":", 1) for c in (a.config or ["today:"])]
    if any(len(c) != 2 or not c[0] for c in configs):
        sys.exit('time_to_accuracy: --config takes "NAME:EXTRA FLAGS"')
    print(f"| scene | configuration | " + " | ".join(f"{100 * t:g} %" for t in targets) + " |")
    print("|---|---|" + "---|" * len(targets))
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for name in a.scene or ["box", "office"]:
            scene = (box_room(folder) if name == "box" else office(folder) if name == "office"
                     else Path(name).resolve())
            ref_n = int(a.reference_photons)
            ref = reference(a.cli, scene, ref_n, shlex.split(a.reference_flags), a.cache)
            lit = [(e, s) for e, s in ref if e > 0]
            ref_rms = math.sqrt(sum((s / e) ** 2 for e, s in lit) / len(lit))
            label = (f"{scene.stem} (ref. {ref_n:.0e}: rms σ {100 * ref_rms:.2f} %, "
                     f"{len(ref)} cells)")
            searches = [Search(a.cli, scene, shlex.split(flags), ref, a.seeds, folder, a.cache)
                        for _, flags in configs]
            counts = [[s.photons_for(t, a.start, a.bisect, int(a.cap)) for t in targets]
                      for s in searches]
            times = retime(searches, counts, a.repeats)
            for (cname, flags), row_n, row_t in zip(configs, counts, times):
                row = [f"{w:.3f} s / {c:.3f} s ({n:.2g} ph)" if n else "—"
                       for n, (w, c) in zip(row_n, [x or (0.0, 0.0) for x in row_t])]
                print(f"| {label} | {cname} `{flags}` | " + " | ".join(row) + " |", flush=True)
                label = ""
            for (cname, _), row_t in zip(configs[1:], times[1:]):
                ratios = [f"{base[0] / x[0]:.2f}× / {base[1] / x[1]:.2f}×" if base and x else "—"
                          for base, x in zip(times[0], row_t)]
                print(f"| | time of {configs[0][0]} / {cname} (wall / CPU) | " +
                      " | ".join(ratios) + " |", flush=True)


if __name__ == "__main__":
    main()
