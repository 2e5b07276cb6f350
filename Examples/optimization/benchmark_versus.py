#!/usr/bin/python3
"""Table II per evaluation, two builds interleaved (issue 28, third round).

Usage: benchmark_versus.py AFTER_CLI BEFORE_CLI [--threads 1] [--rounds 2] [--cap 900]
       [--scenes hangar cornell conference] [--iterations conference=150]

Runs, scene by scene and round by round, interleaved:
  table2  BEFORE_CLI --next-event off --refine-stage-photons 0  (Table II as the paper refines)
  before  BEFORE_CLI --next-event auto                           (its default staging)
  after   AFTER_CLI  --next-event auto  [AFTER_FLAGS]            (this build's staging)
  matched AFTER_CLI  --next-event auto --match-widths true       (and N at equal widths)
with the load average before each run; per configuration the fastest round, by wall time and
by the run's CPU time (user + system: with --threads 1 close to an idle core's wall time). Milliseconds per
evaluation count each configuration the search evaluated once, as an unstaged search counts it:
evaluations - stage traces + members left out (a member traced at N/4, N/2 and N is one
evaluation, and so is one left out after N/4, which unstaged would have had its N trace).
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import resource

from benchmark import run


def per_config_ms(c: dict) -> float:
    """Milliseconds per configuration evaluated (see the module's docstring)."""
    n = c["evaluations"] - c.get("refine_stage", 0) + c.get("refine_dropped", 0)
    return 1e3 * c["total_seconds"] / max(n, 1)


def cpu_seconds() -> float:
    """CPU seconds (user + system) of the finished child processes so far: with --threads 1 a
    run's CPU time is close to its time on an idle core, whatever the load."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("after_cli")
    ap.add_argument("before_cli")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--cap", type=float, default=900.0)
    ap.add_argument("--scenes", nargs="+", default=["hangar", "cornell", "conference"])
    ap.add_argument("--iterations", nargs="*", default=[],
                    help="scene=iterations (default: the scene's 1000)")
    ap.add_argument("--after-flags", default="", help="extra flags for the after build")
    ap.add_argument("--skip", nargs="*", default=[], help="configurations to leave out")
    a = ap.parse_args()
    iterations = {k: int(v) for k, v in (s.split("=") for s in a.iterations)}
    configs = {
        "table2": (a.before_cli, ("--next-event", "off", "--refine-stage-photons", "0")),
        "before": (a.before_cli, ("--next-event", "auto")),
        "after": (a.after_cli, ("--next-event", "auto", *a.after_flags.split())),
        "matched": (a.after_cli, ("--next-event", "auto", "--match-widths", "true",
                                  *a.after_flags.split())),
    }
    configs = {k: v for k, v in configs.items() if k not in a.skip}
    print(f"machine: {platform.processor() or platform.machine()}, {a.threads} threads, "
          f"{os.cpu_count()} CPUs", flush=True)
    runs: dict[tuple[str, str], list[dict]] = {}
    for rnd in range(a.rounds):
        for scene in a.scenes:
            for name, (cli, extra) in configs.items():
                load = os.getloadavg()[0]
                cpu0 = cpu_seconds()
                c = run(cli, scene, iterations.get(scene, 1000), False, a.threads, a.cap, extra)
                c["cpu"] = cpu_seconds() - cpu0
                c["load"], c["ms"] = load, per_config_ms(c)
                c["cpu_ms"] = per_config_ms({**c, "total_seconds": c["cpu"]})
                runs.setdefault((scene, name), []).append(c)
                best = c["best"] or {}
                print(f"round {rnd + 1} {scene} {name}: {c['ms']:.2f} ms/evaluation "
                      f"({c['cpu_ms']:.2f} ms CPU), width factor {c['width_factor']}, best "
                      f"interval [{best.get('ci_low')}, {best.get('ci_high')}] with "
                      f"{c['best_photons']} photons, load "
                      f"{load:.2f}, {c['evaluations']} evaluations ({c.get('refine_stage', 0)} "
                      f"stage traces), refined {c['refined']}, left out "
                      f"{c.get('refine_dropped', 0)}, {c['total_seconds']:.1f} s, "
                      f"ISOC {len(c['isoc'])}, best {json.dumps(c['isoc'][:1])}", flush=True)
    for scene in a.scenes:
        best = {n: min(runs[(scene, n)], key=lambda c: c["ms"]) for n in configs}
        cpu = {n: min(r["cpu_ms"] for r in runs[(scene, n)]) for n in configs}
        print(f"\n{scene}:")
        for n, c in best.items():
            print(f"  {n}: {c['ms']:.2f} ms (rounds {[round(r['ms'], 2) for r in runs[(scene, n)]]}"
                  f", load {c['load']:.2f}); CPU {cpu[n]:.2f} ms (rounds "
                  f"{[round(r['cpu_ms'], 2) for r in runs[(scene, n)]]}), photons/evaluation "
                  f"{c['photons_traced'] / max(c['evaluations'] - c.get('refine_stage', 0) + c.get('refine_dropped', 0), 1):.4g}, "
                  f"ISOC {len(c['isoc'])}")
        for n in configs:
            for m in ("after", "matched"):
                if n not in ("after", "matched") and m in best:
                    print(f"  {m} vs {n}: {best[n]['ms'] / best[m]['ms']:.2f}x wall, "
                          f"{cpu[n] / cpu[m]:.2f}x CPU")


if __name__ == "__main__":
    main()
