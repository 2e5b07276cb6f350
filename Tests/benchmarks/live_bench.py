# SPDX-License-Identifier: LGPL-2.1-or-later
"""Live results on the example office (docs/BENCHMARKS.md): seconds from a change to the first
numbers and to every cell and target within +-5 % (worst_cell_relative <= 0.05), at the start,
after a luminaire move, furniture moves (the cabinet: an instance move; the desk, whose top is
a target: a re-export) and a dimming change (a flux
change: a luminaire update until per-group rescaling exists). One run; prints a Markdown table.

    LIGHTSOLVER_PYTHONPATH=build/NativeSolver/python freecadcmd -c \
        "exec(open('Tests/benchmarks/live_bench.py').read())"
"""
import os
import sys
import time

REPO = os.environ.get("LIGHTING_SOURCE_DIR", os.getcwd())
for folder in (os.path.join(REPO, "Workbench"), os.path.join(REPO, "Examples")):
    if folder not in sys.path:
        sys.path.insert(0, folder)

import FreeCAD  # noqa: E402

import lighting  # noqa: E402
import office_model  # noqa: E402

GOAL = 0.05


def measure(live, what):
    """(what, path, seconds to first frame, to the goal, photons at the goal)."""
    first = None
    for frame in live.frames(timeout=300):
        if first is None:
            first = frame.seconds_since_change
        if frame.worst_cell_relative <= GOAL:
            return (what, frame.path, first, frame.seconds_since_change, frame.photons)
    return (what, "-", first, float("nan"), 0)


def main():
    doc = office_model.build_office(photons=1 << 26)
    analysis = doc.getObject("LightingAnalysis")
    analysis.Decide = False
    analysis.TargetAccuracy = 0.0
    rows = []
    live = lighting.LiveSession(doc)
    try:
        rows.append(measure(live, "start (export + BVH)"))
        lum = doc.getObject("Luminaire01")
        lum.Placement.Base = FreeCAD.Vector(2500, 2000, lum.Placement.Base.z)
        rows.append(measure(live, "luminaire moved"))
        cabinet = doc.getObject("Cabinet")
        cabinet.Placement.Base = FreeCAD.Vector(2000, 1500, cabinet.Placement.Base.z)
        rows.append(measure(live, "furniture moved (cabinet: an instance)"))
        desk = doc.getObject("Desk")
        desk.Placement.Base = desk.Placement.Base + FreeCAD.Vector(500, 0, 0)
        doc.recompute()
        rows.append(measure(live, "furniture moved (desk: a target's faces, re-export)"))
        lum.FluxLumen = 0.5 * lum.FluxLumen
        rows.append(measure(live, "dimmed to 50 % (flux)"))
    finally:
        live.stop()
    print("| change | path | first numbers (s) | worst cell <= +-5 % (s) | photons then |")
    print("|---|---|---|---|---|")
    for what, path, first, goal, photons in rows:
        print(f"| {what} | {path} | {first:.2f} | {goal:.2f} | {photons:,} |")


main()
