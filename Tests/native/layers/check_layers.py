#!/usr/bin/env python3
"""The solver's include layers (docs/solver.md, "Layers"), checked on every #include line.

Each folder of NativeSolver/src is a module; LAYERS says which modules each may include.
A project include names its module by its first path component ("core/backend.hpp"); an
include without a folder is the including file's own module. Public headers
("lightsolver/...") are the library's API and allowed everywhere; system and third-party
headers are not the project's and are skipped.

Usage:
  check_layers.py SRC_DIR     check the tree; exit 1 naming every file:line that breaks a rule
  check_layers.py --self-test check the checker on fixture trees (it must catch each rule)
"""

from __future__ import annotations

import re
import sys
import tempfile
from pathlib import Path

# Module -> the modules it may include (itself always). The core, bottom to top: io (JSON reading,
# output files); model (the prepared scene, tallies, the Backend interface); types (one unit per
# luminaire and target type); scene (reading); prepare (check, prepare, effects, reach); estimate
# (statistics, target results, decisions); run (Simulation, stop policies, solve, study); results
# (the results file and rescale). Glare sits above estimate and results and is never included by
# them; the backends implement model's Backend over the prepared scene and never see each other;
# tables assemble the type tables from the rows of types and glare; the optimizer drives runs
# from above, as the annual daylight coefficients do. photometry, daylight (sun position, sky
# models) and mpi stand alone.
_CORE = ["io", "model", "types", "scene", "prepare", "estimate", "run", "results"]
LAYERS: dict[str, set[str]] = {
    "photometry": set(),
    "daylight": set(),
    "mpi": set(),
    "io": set(),
    "model": {"io"},
    "types": {"io", "model", "daylight"},
    "scene": {"io", "model", "types", "daylight"},
    "prepare": {"io", "model", "types", "scene", "daylight"},
    "estimate": {"io", "model", "types"},
    "run": {"io", "model", "types", "scene", "prepare", "estimate", "daylight"},
    "results": {"io", "model", "types", "scene", "estimate"},
    "glare": {"io", "model", "types", "estimate", "results"},
    "embree": {"io", "model", "types", "prepare"},
    "vulkan": {"io", "model", "types", "prepare"},
    "tables": {"io", "model", "types", "estimate", "results", "glare"},
    "optimizer": set(_CORE) | {"glare"},
    "annual": set(_CORE) | {"daylight"},
}

# Why a rule exists, for the message.
_CORE_WHY = ("the core never includes a backend, glare (a layer above the estimates) or the "
             "optimizer, and each of its folders only those below it: reach a layer above "
             "through a table assembled above both (src/tables, backend_list.cpp)")
WHY: dict[str, str] = {m: f"{m} may include only {', '.join(sorted(LAYERS[m] | {m}))}; "
                          f"{_CORE_WHY}" for m in _CORE}
WHY.update({
    "embree": "a backend includes the core's model, types and prepare only, never another "
              "backend",
    "vulkan": "a backend includes the core's model, types and prepare only, never another "
              "backend",
})

INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]')
SOURCES = {".cpp", ".hpp", ".h", ".inc", ".cc"}


def violations(src: Path) -> list[str]:
    """Every include in `src` (NativeSolver/src) that breaks LAYERS, as 'file:line: why'."""
    modules = {p.name for p in src.iterdir() if p.is_dir()}
    found: list[str] = []
    for module in sorted(modules - LAYERS.keys()):
        found.append(f"{src / module}: module '{module}' is not in the layer map "
                     f"(add it to LAYERS in {Path(__file__).name} and docs/solver.md)")
    for path in sorted(src.rglob("*")):
        if path.suffix not in SOURCES or not path.is_file():
            continue
        own = path.relative_to(src).parts[0]
        if len(path.relative_to(src).parts) == 1 or own not in LAYERS:
            continue  # top-level generated lists (backend_list.cpp.in) see every module
        allowed = LAYERS[own] | {own}
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            m = INCLUDE.match(line)
            if not m or "/" not in m.group(1):
                continue
            target = m.group(1).split("/")[0]
            if target in (".", ".."):  # relative: the module it lands in
                landed = (path.parent / m.group(1)).resolve()
                try:
                    target = landed.relative_to(src.resolve()).parts[0]
                except ValueError:
                    continue  # outside src/: not a module
            if target in modules and target not in allowed:
                why = WHY.get(own, f"{own} may include only {', '.join(sorted(allowed))}")
                found.append(f'{path}:{number}: {own} includes "{m.group(1)}" ({target}): {why}')
    return found


def self_test() -> int:
    """Builds fixture trees: a clean one must pass, each broken rule must be named by line."""
    cases = {
        "estimate/a.cpp": ('#include "model/b.hpp"\n#include "glare/g.hpp"\n',
                           "estimate/a.cpp:2:"),
        "model/c.hpp": ('#include <vulkan/v.hpp>\n', "model/c.hpp:1:"),
        "embree/e.cpp": ('#include "model/b.hpp"\n\n#include "vulkan/v.hpp"\n',
                         "embree/e.cpp:3:"),
        "photometry/p.cpp": ('#include "model/b.hpp"\n', "photometry/p.cpp:1:"),
        "estimate/d.cpp": ('#include "../glare/g.hpp"\n', "estimate/d.cpp:1:"),
        "model/f.cpp": ('#include "run/r.hpp"\n', "model/f.cpp:1:"),
        "results/h.cpp": ('#include "glare/g.hpp"\n', "results/h.cpp:1:"),
        "embree/k.cpp": ('#include "run/r.hpp"\n', "embree/k.cpp:1:"),
    }
    clean = {
        "model/b.hpp": '#include "lightsolver/scene.hpp"\n#include <vector>\n#include "b2.hpp"\n',
        "run/r.hpp": '#include "model/b.hpp"\n#include "estimate/e.hpp"\n',
        "estimate/e.hpp": '#include "model/b.hpp"\n',
        "glare/g.hpp": '#include "estimate/e.hpp"\n',
        "vulkan/v.hpp": '#include "model/b.hpp"\n#include "trace_bindings.h"\n',
        "tables/t.cpp": '#include "model/b.hpp"\n#include "glare/g.hpp"\n',
        "optimizer/o.cpp": '#include "run/r.hpp"\n',
        "mpi/m.cpp": "#include <mpi.h>\n",
        "photometry/q.cpp": '#include "photometry_internal.hpp"\n',
        "glare/h.cpp": '#include "../model/b.hpp"\n#include "./g.hpp"\n',
    }
    failures: list[str] = []
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp) / "src"
        for rel, text in clean.items():
            (root / rel).parent.mkdir(parents=True, exist_ok=True)
            (root / rel).write_text(text)
        if violations(root):
            failures.append(f"clean fixture flagged: {violations(root)}")
        for rel, (text, expected) in cases.items():
            (root / rel).parent.mkdir(parents=True, exist_ok=True)
            (root / rel).write_text(text)
            found = violations(root)
            if len(found) != 1 or expected not in found[0].replace("\\", "/"):
                failures.append(f"{rel}: expected one violation at {expected}, got {found}")
            (root / rel).unlink()
        (root / "newmodule").mkdir()
        found = violations(root)
        if len(found) != 1 or "not in the layer map" not in found[0]:
            failures.append(f"an unmapped module must be named, got {found}")
    for f in failures:
        print("self-test FAILED:", f)
    if not failures:
        print(f"self-test passed: {len(cases)} broken rules caught, clean tree accepted")
    return 1 if failures else 0


def main(argv: list[str]) -> int:
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) != 2:
        print(__doc__)
        return 2
    found = violations(Path(argv[1]))
    for f in found:
        print(f)
    if found:
        print(f"{len(found)} include(s) break the layers (docs/solver.md, 'Layers')")
        return 1
    print("include layers: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
