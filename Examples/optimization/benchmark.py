#!/usr/bin/python3
"""Table II of Avas & Fernandez for the three examples: time per iteration split into
acceleration-structure update, photon tracing and the rest, with adaptive n/N (the scene's
search block) versus a static N (every candidate traced with N), and the speedup.

An "iteration" of the paper is one configuration applied and traced (Fig. 4), i.e. one
evaluation here; per VNS iteration figures are printed too. Runs `lightsolver optimize` with
--threads (default 2) and a wall-clock cap per run (SIGINT: the run stops and reports what it
did). Usage: benchmark.py PATH/TO/lightsolver [--threads 2] [--cap 300] [--reuse]

--reuse: instead, the adaptive runs with reused group traces (the default) against
--no-reuse (every group traced for every evaluation), with the photons actually traced per
evaluation; small_room (a flux variable) is added.
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
REUSE_SCENES = ["cornell", "hangar", "conference", "small_room"]


def run(cli: str, scene: str, iterations: int | None, static: bool, threads: int, cap: float,
        extra: tuple[str, ...] = ()) -> dict:
    """One optimize run (iterations None: the scene's own); returns its counters."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "r.json"
        cmd = [cli, "optimize", str(HERE / scene / f"{scene}.json"), "--quiet", "--threads",
               str(threads), "--out", str(out), *extra]
        if iterations is not None:
            cmd += ["--iterations", str(iterations)]
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


def reuse_table(a: argparse.Namespace) -> None:
    """Adaptive n/N with and without reused group traces, one run each, one after the other."""
    rows = {}
    for scene in REUSE_SCENES:
        iterations = None if scene == "small_room" else 1000
        before = run(a.cli, scene, iterations, False, a.threads, a.cap, ("--no-reuse",))
        after = run(a.cli, scene, iterations, False, a.threads, a.cap)
        rows[scene] = (before, after)
        print(scene, json.dumps({"no_reuse": before, "reuse": after}), flush=True)
    print("\n| per evaluation | " + " | ".join(rows) + " |")
    print("|---|" + "---|" * len(rows))

    def line(label: str, f) -> None:
        print(f"| {label} | " + " | ".join(f(b, r) for b, r in rows.values()) + " |")

    line("evaluations (no reuse / reuse)", lambda b, r: f"{b['evaluations']} / {r['evaluations']}")
    line("photons requested", lambda b, r: f"{b['photons'] / max(b['evaluations'], 1):.4g}")
    line("photons traced, no reuse",
         lambda b, r: f"{b['photons_traced'] / max(b['evaluations'], 1):.4g}")
    line("photons traced, reuse",
         lambda b, r: f"{r['photons_traced'] / max(r['evaluations'], 1):.4g}")
    line("ms, no reuse (before)", lambda b, r: f"{per_eval(b)['total']:.2f}")
    line("ms, reuse (after)", lambda b, r: f"{per_eval(r)['total']:.2f}")
    line("speedup", lambda b, r: f"{per_eval(b)['total'] / max(per_eval(r)['total'], 1e-9):.2f}")
    line("run seconds (no reuse / reuse)",
         lambda b, r: f"{b['total_seconds']:.1f} / {r['total_seconds']:.1f}")
    for scene, (b, r) in rows.items():
        print(f"{scene}: ISOC no reuse {len(b['isoc'])} {b['isoc'][:3]}; "
              f"reuse {len(r['isoc'])} {r['isoc'][:3]}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--cap", type=float, default=300.0)
    ap.add_argument("--reuse", action="store_true",
                    help="reused group traces against --no-reuse (issue 15)")
    a = ap.parse_args()
    print(f"machine: {platform.processor() or platform.machine()}, {a.threads} threads")
    if a.reuse:
        reuse_table(a)
        return
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
