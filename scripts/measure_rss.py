#!/usr/bin/env python3
"""Peak resident memory of `lightsolver run` at several photon counts.

No photon map is stored, so memory must not grow with the photon count. Usage:
    /usr/bin/python3 scripts/measure_rss.py [SCENE] [PHOTONS ...]
"""
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def peak_rss_mib(cmd: list) -> tuple:
    """Runs cmd in a child; returns (peak RSS of that child in MiB, seconds)."""
    start = time.monotonic()
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    # ru_maxrss of children is the maximum over all waited-for children: run the smallest first.
    return max(before, after) / 1024.0, time.monotonic() - start


def main() -> None:
    scene = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "Examples/room/room.json")
    counts = [int(float(x)) for x in sys.argv[2:]] or [10**6, 10**8]
    cli = str(ROOT / "build/NativeSolver/cli/lightsolver")
    print(f"{'photons':>12} {'peak RSS [MiB]':>15} {'seconds':>9}")
    for n in sorted(counts):
        rss, secs = peak_rss_mib([cli, "run", scene, "--photons", str(n), "-q"])
        print(f"{n:>12} {rss:>15.1f} {secs:>9.1f}")


if __name__ == "__main__":
    main()
