#!/usr/bin/python3
"""Table II per evaluation, two builds interleaved (issue 28, third round).

Usage: benchmark_versus.py AFTER_CLI BEFORE_CLI [--threads 1] [--rounds 2] [--cap 900]
       [--scenes hangar cornell conference] [--iterations conference=150]

Runs, scene by scene and round by round, interleaved:
  table2  BEFORE_CLI --next-event off --refine-stage-photons 0  (Table II as the paper refines)
  before  BEFORE_CLI --next-event auto                           (its default staging)
  after   AFTER_CLI  --next-event auto  [AFTER_FLAGS]            (this build's staging)
with the load average before each run; per configuration the fastest round. Milliseconds per
evaluation count each configuration the search evaluated once, as an unstaged search counts it:
evaluations - stage traces + members left out (a member traced at N/4, N/2 and N is one
evaluation, and so is one left out after N/4, which unstaged would have had its N trace).
"""
from __future__ import annotations

import argparse
import json
import os
import platform

from benchmark import run


def per_config_ms(c: dict) -> float:
    """Milliseconds per configuration evaluated (see the module's docstring)."""
    n = c["evaluations"] - c.get("refine_stage", 0) + c.get("refine_dropped", 0)
    return 1e3 * c["total_seconds"] / max(n, 1)


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
    }
    configs = {k: v for k, v in configs.items() if k not in a.skip}
    print(f"machine: {platform.processor() or platform.machine()}, {a.threads} threads, "
          f"{os.cpu_count()} CPUs", flush=True)
    runs: dict[tuple[str, str], list[dict]] = {}
    for rnd in range(a.rounds):
        for scene in a.scenes:
            for name, (cli, extra) in configs.items():
                load = os.getloadavg()[0]
                c = run(cli, scene, iterations.get(scene, 1000), False, a.threads, a.cap, extra)
                c["load"], c["ms"] = load, per_config_ms(c)
                runs.setdefault((scene, name), []).append(c)
                print(f"round {rnd + 1} {scene} {name}: {c['ms']:.2f} ms/evaluation, load "
                      f"{load:.2f}, {c['evaluations']} evaluations ({c.get('refine_stage', 0)} "
                      f"stage traces), refined {c['refined']}, left out "
                      f"{c.get('refine_dropped', 0)}, {c['total_seconds']:.1f} s, "
                      f"ISOC {len(c['isoc'])}, best {json.dumps(c['isoc'][:1])}", flush=True)
    for scene in a.scenes:
        best = {n: min(runs[(scene, n)], key=lambda c: c["ms"]) for n in configs}
        print(f"\n{scene}:")
        for n, c in best.items():
            print(f"  {n}: {c['ms']:.2f} ms (rounds {[round(r['ms'], 2) for r in runs[(scene, n)]]}"
                  f", load {c['load']:.2f}), photons/evaluation "
                  f"{c['photons_traced'] / max(c['evaluations'] - c.get('refine_stage', 0) + c.get('refine_dropped', 0), 1):.4g}, "
                  f"ISOC {len(c['isoc'])}")
        for n in configs:
            if n != "after" and "after" in best:
                print(f"  after vs {n}: {best[n]['ms'] / best['after']['ms']:.2f}x")


if __name__ == "__main__":
    main()
