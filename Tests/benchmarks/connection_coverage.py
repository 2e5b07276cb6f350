# SPDX-License-Identifier: LGPL-2.1-or-later
"""Per-cell coverage of the intervals with connected reflected light (docs/statistics.md,
"Connected reflected light at grids"): the issue's box room (time_to_accuracy.py's, 16 x 16
cells) over SEEDS seeds of N photons with `--next-event on --connect-reflections on`, each cell's
95 %, 99 % and 99.9 % interval against a reference run of 64 N photons (seed 999, the same
estimator; its own sigma, 1/8 of a run's, lowers the coverage by about 0.2 %).

    /usr/bin/python3 Tests/benchmarks/connection_coverage.py [--cli PATH] [--photons N]
        [--seeds S]

Slow (S + 64 runs' worth of photons; 100 seeds of 1e5 photons: a few minutes on 2 cores), so it
is a benchmark whose result docs/statistics.md records, not a CTest entry; the cheap check is
ReflectionConnection.PerCellCoverageOver200Seeds (Tests/native/core).
"""
import argparse
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import time_to_accuracy  # noqa: E402  (the box room's one definition)

FLAGS = ["--next-event", "on", "--connect-reflections", "on"]
Z = {95: 1.959963984540054, 99: 2.5758293035489, 99.9: 3.2905267314919}


def cells(cli: str, scene: Path, photons: int, seed: int, out: Path) -> list:
    """The grid's cells of one run: (lux, ci_low, ci_high) at 95 %."""
    subprocess.run([cli, "run", str(scene), "--photons", str(photons), "--seed", str(seed),
                    "--out", str(out), "-q"] + FLAGS, check=True)
    grid = next(t for t in json.loads(out.read_text())["targets"] if t["type"] == "grid")
    return [(c["lux"], c["ci_low_lux"], c["ci_high_lux"]) for c in grid["cells"]]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default_cli = time_to_accuracy.ROOT / "build/NativeSolver/cli/lightsolver"
    ap.add_argument("--cli", default=str(default_cli))
    ap.add_argument("--photons", type=int, default=100_000)
    ap.add_argument("--seeds", type=int, default=100)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        scene = time_to_accuracy.box_room(folder)
        out = folder / "run.json"
        ref = cells(a.cli, scene, 64 * a.photons, 999, out)
        covered, z = 0, []
        for seed in range(1, a.seeds + 1):
            for (e, lo, hi), (r, _, _) in zip(cells(a.cli, scene, a.photons, seed, out), ref):
                covered += lo <= r <= hi
                z.append((e - r) / ((hi - lo) / (2 * Z[95])))
    n = len(z)
    print(f"{a.photons} photons, {a.seeds} seeds, {n} cell intervals: 95 % covers "
          f"{100 * covered / n:.2f} % (binomial sd {100 * math.sqrt(0.95 * 0.05 / n):.2f} %)")
    for q, zq in Z.items():
        print(f"  outside the {q} % interval (by its half-width): "
              f"{100 * sum(abs(x) > zq for x in z) / n:.3f} % (nominal {100 - q:.1f} %)")
    print(f"  rms z {math.sqrt(sum(x * x for x in z) / n):.3f}, mean z {sum(z) / n:+.4f}")


if __name__ == "__main__":
    main()
