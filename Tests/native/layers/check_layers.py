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

# Module -> the modules it may include (itself always). Bottom to top: photometry and mpi
# stand alone; core (scene, prepare, run, estimate) sees neither a backend nor glare; glare
# sits above the estimate layer; backends (embree, vulkan) implement core's Backend and never
# see each other; tables assemble the type tables from the rows of core and glare; the
# optimizer drives runs from above.
LAYERS: dict[str, set[str]] = {
    "photometry": set(),
    "mpi": set(),
    "core": set(),
    "glare": {"core"},
    "embree": {"core"},
    "vulkan": {"core"},
    "tables": {"core", "glare"},
    "optimizer": {"core", "glare"},
}

# Why a rule exists, for the message.
WHY: dict[str, str] = {
    "core": "core (the estimate layer and below) never includes a backend, glare (a layer "
    "above it) or the optimizer: register through a table assembled above it "
    "(src/tables, backend_list.cpp)",
    "embree": "a backend includes core only, never another backend",
    "vulkan": "a backend includes core only, never another backend",
}

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
        "core/a.cpp": ('#include "core/b.hpp"\n#include "glare/g.hpp"\n', "core/a.cpp:2:"),
        "core/c.hpp": ('#include <vulkan/v.hpp>\n', "core/c.hpp:1:"),
        "embree/e.cpp": ('#include "core/b.hpp"\n\n#include "vulkan/v.hpp"\n', "embree/e.cpp:3:"),
        "photometry/p.cpp": ('#include "core/b.hpp"\n', "photometry/p.cpp:1:"),
        "core/d.cpp": ('#include "../glare/g.hpp"\n', "core/d.cpp:1:"),
    }
    clean = {
        "core/b.hpp": '#include "lightsolver/scene.hpp"\n#include <vector>\n#include "b2.hpp"\n',
        "glare/g.hpp": '#include "core/b.hpp"\n',
        "vulkan/v.hpp": '#include "core/b.hpp"\n#include "trace_bindings.h"\n',
        "tables/t.cpp": '#include "core/b.hpp"\n#include "glare/g.hpp"\n',
        "optimizer/o.cpp": '#include "core/b.hpp"\n',
        "mpi/m.cpp": "#include <mpi.h>\n",
        "photometry/q.cpp": '#include "photometry_internal.hpp"\n',
        "glare/h.cpp": '#include "../core/b.hpp"\n#include "./g.hpp"\n',
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
