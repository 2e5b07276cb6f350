#!/usr/bin/env python3
"""Start-up of ``lightsolver run`` on the furnished office (docs/BENCHMARKS.md, "Start-up").

The office is Examples/optimization/conference (room, table, 28 chairs, podium: 65,806
triangles) in two forms: as shipped (three binary PLY meshes beside the JSON) and with every
mesh inline in the JSON, as the workbench writes scenes below its PLY threshold, plus a
work-plane grid at 0.8 m. Each run is ``lightsolver run SCENE --photons 1000 -q --timings``;
the script prints the median of each phase over the runs, the time from its own clock just
before the process starts to main (the same CLOCK_MONOTONIC), to the first photon and to the
process's exit, and the process's CPU time (user + system, all threads).

    python3 scripts/startup_bench.py [--binary build/NativeSolver/cli/lightsolver] [--runs 7]
        [--backend auto] [--backend embree] [--compare OTHER_BINARY]

With --compare the two binaries run interleaved (same machine load) and each one's medians
print side by side.
"""
import argparse
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from typing import Dict, List, Tuple

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OFFICE = os.path.join(ROOT, "Examples", "optimization", "conference", "conference.json")


def read_ply(path: str) -> Tuple[List[List[float]], List[List[int]]]:
    """Vertices and triangles of a binary little-endian PLY (float x y z; uchar/int lists)."""
    import struct

    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").split("\n")
    nv = int(next(l for l in header if l.startswith("element vertex")).split()[2])
    nf = int(next(l for l in header if l.startswith("element face")).split()[2])
    verts = struct.unpack_from(f"<{3 * nv}f", data, end)
    vertices = [[verts[3 * i], verts[3 * i + 1], verts[3 * i + 2]] for i in range(nv)]
    at, triangles = end + 12 * nv, []
    for _ in range(nf):
        assert data[at] == 3, "triangles only"
        triangles.append(list(struct.unpack_from("<3i", data, at + 1)))
        at += 13
    return vertices, triangles


def inline_office(folder: str) -> str:
    """The office with its PLY meshes inline (floats as the exporter writes them) and a grid."""
    with open(OFFICE) as f:
        scene = json.load(f)
    base = os.path.dirname(OFFICE)
    for mesh in scene["meshes"]:
        if "file" in mesh:
            vertices, triangles = read_ply(os.path.join(base, mesh.pop("file")))
            mesh["vertices"], mesh["triangles"] = vertices, triangles
    scene["targets"].append({"name": "workplane", "type": "grid", "corner": [0.5, 0.5, 0.8],
                             "edge1": [11.0, 0.0, 0.0], "edge2": [0.0, 7.0, 0.0],
                             "cells": [22, 14]})
    scene.pop("optimization", None)
    path = os.path.join(folder, "office_inline.json")
    # As the workbench writes it (lighting/export/scene.py dumps_scene): indented, each mesh's
    # arrays on one line.
    arrays = {}
    for i, mesh in enumerate(scene["meshes"]):
        for key in ("vertices", "triangles"):
            token = f"@@mesh{i}.{key}@@"
            arrays[f'"{token}"'] = json.dumps(mesh[key], separators=(",", ":"))
            mesh[key] = token
    text = json.dumps(scene, indent=2)
    for token, value in arrays.items():
        text = text.replace(token, value, 1)
    with open(path, "w") as f:
        f.write(text)
    return path


LINE = re.compile(r"^  (\s*)(.+?)\s{2,}(-?[0-9.]+)?\s+(-?[0-9.]+)$")


def one_run(binary: str, scene: str, backend: str) -> Dict[str, float]:
    """Phase -> ms of one run, plus 'start to main', 'start to first photon', 'start to exit'."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    p = subprocess.run([binary, "run", scene, "--photons", "1000", "--backend", backend, "-q",
                        "--timings"], capture_output=True, text=True, check=True)
    t_exit = time.monotonic()
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    out: Dict[str, float] = {}
    main_at = None
    parents: List[str] = []  # the phase names above this line, so two "validate" stay apart
    for line in p.stderr.splitlines():
        if line.strip().startswith("main at CLOCK_MONOTONIC"):
            main_at = float(line.split()[-1])
            continue
        m = LINE.match(line)
        if not m:
            continue
        indent, name, ms, end = m.groups()
        depth = len(indent) // 2
        name = re.sub(r" \(x\d+\)$", "", name)
        parents = parents[:depth] + [name]
        key = "  " * depth + name + "\t" + "/".join(parents)  # shown up to the tab
        out[key] = float(ms) if ms is not None else float(end)
    assert main_at is not None, p.stderr
    start_to_main = main_at - 1e3 * t0
    out["start to main"] = start_to_main
    ready = next(v for k, v in out.items() if k.strip().startswith("ready to trace"))
    out["start to first photon"] = start_to_main + ready
    out["start to exit"] = 1e3 * (t_exit - t0)
    # CPU time is less at the mercy of other jobs on a shared machine than wall time.
    out["process CPU time, start to exit"] = 1e3 * (after.ru_utime + after.ru_stime -
                                                    before.ru_utime - before.ru_stime)
    return out


def medians(runs: List[Dict[str, float]]) -> Dict[str, float]:
    keys = list(runs[0])
    return {k: statistics.median(r[k] for r in runs if k in r) for k in keys}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--binary", default=os.path.join(ROOT, "build/NativeSolver/cli/lightsolver"))
    ap.add_argument("--compare", help="a second binary, run interleaved with the first")
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--backend", action="append")
    ap.add_argument("--scene", action="append", help="default: the office, PLY and inline")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        scenes = args.scene or [OFFICE, inline_office(tmp)]
        binaries = [args.binary] + ([args.compare] if args.compare else [])
        for scene in scenes:
            for backend in args.backend or ["auto", "embree"]:
                runs: Dict[str, List[Dict[str, float]]] = {b: [] for b in binaries}
                for _ in range(args.runs):
                    for b in binaries:
                        runs[b].append(one_run(b, scene, backend))
                table = {b: medians(r) for b, r in runs.items()}
                print(f"\n{os.path.basename(scene)}, --backend {backend}, medians of "
                      f"{args.runs} runs (ms)")
                keys = list(dict.fromkeys(k for t in table.values() for k in t))
                labels = ["binary", "compare"][:len(binaries)]
                print(f"  {'phase':44}" + "".join(f"{label:>12}" for label in labels))
                for k in keys:
                    cells = "".join(f"{t[k]:12.2f}" if k in t else f"{'':>12}"
                                    for t in table.values())
                    print(f"  {k.split(chr(9))[0]:44}{cells}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
