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

--nee [--rounds R]: instead, issue 28's Table II before and after: "before" is the search as it
was (--next-event off --refine-stage-photons 0: direct light by photons, every n-level member
traced with N at the end), "after" next-event estimation (--next-event auto) and the staged end
refinement (the default, N/4 first), run interleaved scene by scene, R rounds, with the load
average before each run; per configuration the minimum over the rounds. A staged member's two
traces count as one evaluation (the denominator is the search's evaluations as before staging).
"""
from __future__ import annotations

import argparse
import json
import os
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
    c["next_event"] = r.get("next_event", {})
    c["width_factor"] = r.get("provenance", {}).get("options", {}).get("width_factor")
    c["best"] = r["isoc"][0]["objective"] if r["isoc"] else None
    c["best_photons"] = r["isoc"][0]["photons"] if r["isoc"] else None
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


NEE_CONFIGS = {"before": ("--next-event", "off", "--refine-stage-photons", "0"),
               "after": ("--next-event", "auto")}


def search_ms(c: dict) -> float:
    """Milliseconds per evaluation of the search, a staged member's two traces counted once."""
    return 1e3 * c["total_seconds"] / max(c["evaluations"] - c.get("refine_stage", 0), 1)


def nee_table(a: argparse.Namespace) -> None:
    """Issue 28: before (photons only, unstaged) and after (NEE, staged), interleaved."""
    runs: dict[tuple[str, str], list[dict]] = {}
    for rnd in range(a.rounds):
        for scene, iterations, _ in RUNS:
            for name, extra in NEE_CONFIGS.items():
                load = os.getloadavg()[0]
                c = run(a.cli, scene, iterations, False, a.threads, a.cap, extra)
                c["load"] = load
                c["ms"] = search_ms(c)
                runs.setdefault((scene, name), []).append(c)
                print(f"round {rnd + 1} {scene} {name}: {c['ms']:.2f} ms/evaluation, load "
                      f"{load:.2f}, {c['evaluations']} evaluations, refined {c['refined']}, "
                      f"ISOC {len(c['isoc'])}", flush=True)
    best = {k: min(v, key=lambda c: c["ms"]) for k, v in runs.items()}
    scenes = [scene for scene, _, _ in RUNS]
    print("\n| per evaluation (min over rounds) | " + " | ".join(
        f"{s} before | {s} after" for s in scenes) + " |")
    print("|---|" + "---|---|" * len(scenes))

    def line(label: str, f) -> None:
        print(f"| {label} | " + " | ".join(f(best[(s, 'before')]) + " | " + f(best[(s, 'after')])
                                         for s in scenes) + " |")

    line("ms per evaluation", lambda c: f"{c['ms']:.2f}")
    line("load average before the run", lambda c: f"{c['load']:.2f}")
    line("evaluations (first-stage traces)",
         lambda c: f"{c['evaluations']} ({c.get('refine_stage', 0)})")
    line("N traces at the end (left out)",
         lambda c: f"{c['refined']} ({c.get('refine_dropped', 0)})")
    line("photons per evaluation",
         lambda c: f"{c['photons_traced'] / max(c['evaluations'] - c.get('refine_stage', 0), 1):.4g}")
    line("whole search, s", lambda c: f"{c['total_seconds']:.1f}")
    line("ISOC size", lambda c: f"{len(c['isoc'])}")
    line("best member", lambda c: json.dumps(c["isoc"][0]) if c["isoc"] else "-")
    line("next-event estimation", lambda c: "on" if c.get("next_event", {}).get("direct") else "off")
    for s in scenes:
        b, r = best[(s, "before")], best[(s, "after")]
        print(f"{s}: {b['ms'] / r['ms']:.2f}x per evaluation; all rounds before "
              f"{[round(c['ms'], 2) for c in runs[(s, 'before')]]}, after "
              f"{[round(c['ms'], 2) for c in runs[(s, 'after')]]}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--cap", type=float, default=300.0)
    ap.add_argument("--reuse", action="store_true",
                    help="reused group traces against --no-reuse (issue 15)")
    ap.add_argument("--nee", action="store_true",
                    help="next-event estimation and the staged refinement against neither "
                         "(issue 28), interleaved")
    ap.add_argument("--rounds", type=int, default=2, help="--nee: rounds of the interleaving")
    a = ap.parse_args()
    print(f"machine: {platform.processor() or platform.machine()}, {a.threads} threads")
    if a.reuse:
        reuse_table(a)
        return
    if a.nee:
        nee_table(a)
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
