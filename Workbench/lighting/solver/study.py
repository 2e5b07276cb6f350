# SPDX-License-Identifier: LGPL-2.1-or-later
"""What accuracy costs for an analysis: ``lightsolver study`` on its exported scene (one run
with doubling checkpoints: per-cell interval width against time, the N^-1/2 fit, and the
photons and seconds each per-cell accuracy needs), with its plot. App code: scripts and the
task panel use the same function; the solver draws the plot (docs/accuracy.md)."""
from __future__ import annotations

import json
import os
import subprocess
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

from lighting.messages import SolverError
from lighting.solver import run

#: Photons of the study's last checkpoint (doubling from 10^4): seconds on a laptop.
DEFAULT_MAX_PHOTONS = 1_280_000


@dataclass
class StudyResult:
    """The study of one scene: its rows, the accuracy goals and where the files are."""

    data: Dict[str, Any]
    json_file: str
    plot_file: str
    text: str = ""
    goals: List[Dict[str, Any]] = field(default_factory=list)

    def goals_text(self) -> str:
        """One line per per-cell accuracy: photons and seconds (extrapolated ones marked)."""
        lines = []
        for goal in self.goals:
            mark = " (extrapolated)" if goal.get("extrapolated") else ""
            lines.append(f"\u00b1{100.0 * goal['accuracy']:g} % per cell: "
                         f"{goal['photons']:.3g} photons, {goal['seconds']:.3g} s{mark}")
        return "\n".join(lines)


def study_scene(scene_file: str, max_photons: int = DEFAULT_MAX_PHOTONS,
                out_dir: Optional[str] = None, timeout_s: float = 600.0) -> StudyResult:
    """Run ``lightsolver study`` on a scene file; the JSON and a PNG plot go next to it (or
    into ``out_dir``). Raises SolverError naming what is missing or what failed."""
    cli = run.cli_executable()
    if cli is None:
        raise SolverError("the accuracy study needs the lightsolver program: build it, or set "
                          f"{run.ENV_CLI}")
    folder = out_dir or os.path.dirname(os.path.abspath(scene_file))
    json_file = os.path.join(folder, "study.json")
    plot_file = os.path.join(folder, "study.png")
    cmd = [cli, "study", scene_file, "--max-photons", str(int(max_photons)), "--json",
           json_file, "--plot", plot_file]
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout_s,
                              check=False)
    except (OSError, subprocess.TimeoutExpired) as exc:
        raise SolverError(f"lightsolver study failed: {exc}") from exc
    if proc.returncode != 0 or not os.path.isfile(json_file):
        message = (proc.stderr or proc.stdout).strip().splitlines()
        raise SolverError("lightsolver study failed: " + (message[-1] if message else
                                                           f"exit status {proc.returncode}"))
    with open(json_file, encoding="utf-8") as stream:
        data = json.load(stream)
    return StudyResult(data=data, json_file=json_file, plot_file=plot_file, text=proc.stdout,
                       goals=list(data.get("goals", [])))


def study_analysis(analysis: Any, max_photons: int = DEFAULT_MAX_PHOTONS,
                   output_dir: Optional[str] = None) -> StudyResult:
    """Export the analysis' scene (as Run would) and study it."""
    from lighting import api

    scene_file = api.export_scene(analysis.Document, analysis, directory=output_dir)
    return study_scene(scene_file, max_photons)
