#!/usr/bin/python3
"""Table II of Avas & Fernandez for the three examples: time per iteration split into
acceleration-structure update, photon tracing and the rest, with adaptive n/N (the scene's
search block) versus a static N (every candidate traced with N), and the speedup.

An "iteration" of the paper is one configuration applied and traced (Fig. 4), i.e. one
evaluation here; per VNS iteration figures are printed too. Runs `lightsolver optimize` with
--threads (default 2) and a wall-clock cap per run (SIGINT: the run stops and reports what it
did). Usage: benchmark.py PATH/TO/lightsolver [--threads 2] [--cap 300]
"""
from __future__ import annotations

import argparse
import json
import platform
import signal
import subprocess
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
# (scene, adaptive iterations, static iterations); the paper ran 1000 iterations.
RUNS = [("cornell", 1000, 3), ("hangar", 1000, 3), ("conference", 1000, 1)]


def run(cli: str, scene: str, iterations: int, static: bool, threads: int, cap: float) -> dict:
    """One optimize run; returns its counters."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "r.json"
        cmd = [cli, "optimize", str(HERE / scene / f"{scene}.json"), "--quiet", "--threads",
               str(threads), "--iterations", str(iterations), "--out", str(out)]
        if static:
            cmd.append("--static")
        p = subprocess.Popen(cmd, stdout=subprocess.PIPE, text=True)
        try:
            p.communicate(timeout=cap)
        except subprocess.TimeoutExpired:
            p.send_signal(signal.SIGINT)  # stops within one trace; the ISOC so far is written
            p.communicate()
        r = json.loads(out.read_text())
    c = r["counters"]
    c["isoc"] = [m.get("scene") for m in r["isoc"]]
    c["stop"] = r["stop"]
    return c


def per_eval(c: dict) -> dict[str, float]:
    """Milliseconds per evaluation (the paper's iteration)."""
    n = max(c["evaluations"], 1)
    return {k: 1e3 * c[f"{k}_seconds"] / n for k in ("update", "trace", "other", "total")}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--cap", type=float, default=300.0)
    a = ap.parse_args()
    print(f"machine: {platform.processor() or platform.machine()}, {a.threads} threads")
    rows = {}
    for scene, it_adaptive, it_static in RUNS:
        ad = run(a.cli, scene, it_adaptive, False, a.threads, a.cap)
        st = run(a.cli, scene, it_static, True, a.threads, a.cap)
        rows[scene] = (ad, st)
        print(scene, json.dumps({"adaptive": ad, "static": st}))
    print("\n| ms per evaluation | " + " | ".join(rows) + " |")
    print("|---|" + "---|" * len(rows))
    for label, key in (("acceleration-structure update", "update"), ("photon tracing", "trace"),
                       ("rest (search, ISOC, reduction)", "other"), ("total, adaptive n/N", "total")):
        print(f"| {label} | " + " | ".join(f"{per_eval(ad)[key]:.2f}" for ad, _ in rows.values())
              + " |")
    print("| total, static N | " + " | ".join(f"{per_eval(st)['total']:.1f}"
                                              for _, st in rows.values()) + " |")
    print("| speedup | " + " | ".join(f"{per_eval(st)['total'] / per_eval(ad)['total']:.1f}"
                                      for ad, st in rows.values()) + " |")
    for scene, (ad, st) in rows.items():
        print(f"{scene}: adaptive {ad['iterations']} VNS iterations ({ad['stop']}), "
              f"{ad['evaluations']} evaluations, {ad['confirmations']} with N, "
              f"{ad['photons']:.3g} photons, {ad['total_seconds']:.1f} s; "
              f"{1e3 * ad['total_seconds'] / max(ad['iterations'], 1):.1f} ms per VNS iteration; "
              f"ISOC {ad['isoc'][:4]}")


if __name__ == "__main__":
    main()
