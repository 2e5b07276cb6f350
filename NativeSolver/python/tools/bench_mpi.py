#!/usr/bin/python3
"""Measure one scene under mpirun on this machine (docs/cluster.md): 1 rank x all threads, K
ranks x 1 thread, and K ranks oversubscribed; one run each, ratios from the same run.

    bench_mpi.py LIGHTSOLVER SCENE [--photons N] [--ranks 2 3]
Prints a Markdown table: wall seconds of `lightsolver run` (start-up included), the solver's
tracing time and rate, and the bytes one batch's reduction moves (bins x 16 + 32)."""
from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import tempfile
import time
from typing import List, Tuple


def run(command: List[str]) -> Tuple[float, dict]:
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "r.json")
        start = time.perf_counter()
        subprocess.run(command + ["--out", out, "-q"], check=True, capture_output=True)
        wall = time.perf_counter() - start
        with open(out, encoding="utf-8") as handle:
            return wall, json.load(handle)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cli")
    parser.add_argument("scene")
    parser.add_argument("--photons", type=int, default=4_000_000)
    parser.add_argument("--ranks", type=int, nargs="+", default=[2, 3])
    args = parser.parse_args()
    mpirun = shutil.which("mpirun")
    base = [args.cli, "run", args.scene, "--photons", str(args.photons)]
    cores = os.cpu_count() or 1
    rows = [("1 process x %d threads" % cores, base)]
    for k in args.ranks:
        threads = max(1, cores // k)
        label = f"{k} ranks x {threads} thread{'s' if threads > 1 else ''}"
        if k > cores:
            label += " (oversubscribed)"
        rows.append((label, [mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(k)]
                     + base + ["--threads", str(threads)]))
    reference = None
    print(f"scene {os.path.basename(args.scene)}, {args.photons} photons, {cores} cores\n")
    print("| configuration | wall s | tracing s | photons/s | vs 1 process | identical |")
    print("|---|---|---|---|---|---|")
    for label, command in rows:
        wall, data = run(command)
        numbers = [(t["name"], t["mean_lux"], t["ci_low_lux"]) for t in data["targets"]]
        if reference is None:
            reference = (wall, numbers)
        rate = args.photons / data["seconds"]
        print(f"| {label} | {wall:.2f} | {data['seconds']:.2f} | {rate:.3g} | "
              f"{reference[0] / wall:.2f}x | {'yes' if numbers == reference[1] else 'NO'} |")
    bins = sum(1 + len(t.get("cells") or []) for t in data["targets"])
    print(f"\nreduction per batch: about {bins} bins x 16 bytes = {bins * 16} bytes "
          "(target and cell tallies; mesh bins add one each)")


if __name__ == "__main__":
    main()
