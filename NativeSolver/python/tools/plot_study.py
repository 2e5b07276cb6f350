#!/usr/bin/python3
"""Draw a lightsolver study (``lightsolver study --json``): accuracy against time, log-log.

Usage: ``plot_study.py STUDY.json OUT.png|OUT.svg`` (run by ``lightsolver study --plot``), or
``plot_study(study_dict, path)`` from Python. The x axis is the tracing time of the one run;
the curves are the mean and worst per-cell relative CI half-width and, when the study had a
reference, the mean and max relative error against it. The dashed line is the Monte Carlo rate
N^-1/2 (time is proportional to photons), through the last row's mean half-width.
"""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the non-GUI backend)

#: (row key, label, style) of each curve, in percent.
CURVES: Sequence[Tuple[str, str, Dict[str, Any]]] = (
    ("mean_relative_half_width", "mean cell ± (CI half-width)", {"color": "C0", "marker": "o"}),
    ("worst_relative_half_width", "worst cell ±", {"color": "C0", "marker": "v", "ls": ":"}),
    ("mean_relative_error", "mean cell error vs reference", {"color": "C3", "marker": "s"}),
    ("max_relative_error", "max cell error vs reference", {"color": "C3", "marker": "^",
                                                           "ls": ":"}),
)


def _points(rows: List[Dict[str, Any]], key: str) -> Tuple[List[float], List[float]]:
    """(seconds, percent) of the rows where `key` has a positive value."""
    xs, ys = [], []
    for row in rows:
        value = row["all"].get(key)
        if value is not None and value > 0 and row["seconds"] > 0:
            xs.append(row["seconds"])
            ys.append(100.0 * value)
    return xs, ys


def _title(study: Dict[str, Any]) -> str:
    scene = Path(study.get("scene") or "scene").name
    return (f"{scene}: accuracy against time ({study['backend']}, "
            f"{100 * study['confidence']:.0f}% confidence)")


def plot_study(study: Dict[str, Any], path: str, title: Optional[str] = None) -> None:
    """Write the study's accuracy-against-time plot to `path` (.png or .svg)."""
    rows = study["rows"]
    fig, ax = plt.subplots(figsize=(7.5, 5.0), dpi=120)
    for key, label, style in CURVES:
        xs, ys = _points(rows, key)
        if xs:
            ax.plot(xs, ys, label=label, **style)
    xs, ys = _points(rows, "mean_relative_half_width")
    if xs:
        # width ~ N^-1/2 ~ t^-1/2: through the last point, over the whole time range.
        t0, w0 = xs[-1], ys[-1]
        span = [min(xs), max(xs)]
        ax.plot(span, [w0 * math.sqrt(t0 / t) for t in span], color="0.4", ls="--", lw=1,
                label="N$^{-1/2}$")
    for goal in study.get("goals", []):
        ax.axhline(100 * goal["accuracy"], color="0.85", lw=0.8, zorder=0)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("tracing time [s] (one run; photons double from row to row)")
    ax.set_ylabel("relative to the cell's value [%]")
    fig.suptitle(title or _title(study), fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    # Photons on a secondary axis: the run's rate maps seconds to photons.
    last = rows[-1] if rows else None
    if last and last["seconds"] > 0:
        rate = last["photons"] / last["seconds"]
        top = ax.secondary_xaxis("top", functions=(lambda t: t * rate, lambda n: n / rate))
        top.set_xlabel("photons (at the run's rate)", fontsize=8)
    fig.tight_layout()
    suffix = Path(path).suffix.lower()
    if suffix not in (".png", ".svg"):
        raise ValueError(f"{path}: the plot must be .png or .svg")
    metadata = {"Date": None} if suffix == ".svg" else {"Software": None}
    fig.savefig(path, metadata=metadata)
    plt.close(fig)


def main(argv: Sequence[str]) -> int:
    """Command-line entry: plot_study.py STUDY.json OUT.png|OUT.svg."""
    if len(argv) != 3:
        print("usage: plot_study.py STUDY.json OUT.png|OUT.svg", file=sys.stderr)
        return 2
    try:
        study = json.loads(Path(argv[1]).read_text())
        plot_study(study, argv[2])
    except (OSError, ValueError, KeyError) as e:
        print(f"plot_study.py: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
