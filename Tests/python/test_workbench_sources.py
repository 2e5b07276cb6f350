"""The workbench's sources: every Python file compiles (GUI modules too, which headless tests
never import: a syntax error there would only show as a FreeCAD dialog when the workbench
loads), and no module reads a results document's keys by hand: results are read once, by
``lightsolver_results`` (docs/solver.md, "results"), whose typed objects the workbench uses."""
import ast
import json
import py_compile
from pathlib import Path
from typing import Dict, Iterator, Set, Tuple

import pytest

ROOT = Path(__file__).resolve().parents[2]
WORKBENCH = ROOT / "Workbench"
SOURCES = sorted(WORKBENCH.rglob("*.py"))
SCHEMA = json.loads((ROOT / "docs" / "schemas" / "results.schema.json").read_text())

#: Reads of a result-only key that are not reads of a results document, and what they read.
NOT_RESULTS: Dict[Tuple[str, str], str] = {
    ("lighting/solver/check.py", "warnings"): "lightsolver.check_scene()'s report",
    ("lighting/solver/study.py", "seconds"): "a `lightsolver study` row",
    ("lighting/reporting.py", "warnings"):
        "adds the workbench's notes to the document it hands to the report, which reads it "
        "through lightsolver_results",
}


def _keys_of(node: object, out: Set[str]) -> Set[str]:
    if isinstance(node, dict):
        out.update(node)
        for value in node.values():
            _keys_of(value, out)
    elif isinstance(node, list):
        for value in node:
            _keys_of(value, out)
    return out


def scene_keys() -> Set[str]:
    """The scene format's keys: the solver's run options and type tables (the keys each
    luminaire and target type reads, its requirements), and every key of every scene file in
    the repository (lightsolver.scene/1)."""
    import lightsolver

    found: Set[str] = {str(row["scene_key"]) for row in lightsolver.run_options()
                       if row.get("scene_key")}
    for row in lightsolver.luminaire_types() + lightsolver.target_types():
        found.update(row["keys"])
        found.update(row.get("requirements") or [])
    for path in ROOT.rglob("*.json"):
        if "build" in path.relative_to(ROOT).parts[0]:
            continue
        try:
            doc = json.loads(path.read_text(encoding="utf-8"))
        except (ValueError, UnicodeDecodeError):
            continue
        if isinstance(doc, dict) and str(doc.get("format", "")).startswith("lightsolver.scene"):
            _keys_of(doc, found)
    return found


def result_keys() -> Set[str]:
    """The keys a workbench module may not read: the results schema's (top level, targets,
    cells, the verdict word) that no scene file has, and ``targets`` and ``cells``, which the
    workbench writes into scenes but never reads back from one."""
    defs = SCHEMA["$defs"]
    keys = set(SCHEMA["properties"]) | set(defs["target"]["properties"]) | set(
        defs["cell"]["properties"]) | {"verdict"}
    return (keys - scene_keys()) | {"targets", "cells"}


def key_reads(tree: ast.AST, keys: Set[str]) -> Iterator[Tuple[int, str]]:
    """(line, key) of every ``x["key"]`` read, ``x.get/pop/setdefault("key")`` and
    ``"key" in x`` with a key of ``keys``."""
    for node in ast.walk(tree):
        key = None
        if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and \
                isinstance(node.slice, ast.Constant):
            key = node.slice.value
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and \
                node.func.attr in ("get", "pop", "setdefault") and node.args and \
                isinstance(node.args[0], ast.Constant):
            key = node.args[0].value
        elif isinstance(node, ast.Compare) and isinstance(node.left, ast.Constant) and \
                any(isinstance(op, (ast.In, ast.NotIn)) for op in node.ops):
            key = node.left.value
        if isinstance(key, str) and key in keys:
            yield node.lineno, key


def test_the_workbench_has_sources():
    assert len(SOURCES) > 40


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: str(p.relative_to(WORKBENCH)))
def test_compiles(path, tmp_path):
    py_compile.compile(str(path), cfile=str(tmp_path / "out.pyc"), doraise=True)


def test_the_result_keys_are_the_results_own():
    keys = result_keys()
    # Targets' and cells' statistics, verdicts and run facts are in; scene keys are not.
    assert {"mean_lux", "ci_low_lux", "lux", "uniformity", "verdict", "verdicts", "ugr",
            "partial", "stop_reason", "targets", "cells"} <= keys
    assert not {"name", "type", "requirements", "em_lux", "u0", "flux_lm", "photons",
                "decide"} & keys


def test_the_scan_finds_reads_by_hand():
    planted = ('t = data["targets"][0]\nm = t.get("mean_lux", 0.0)\nif "verdict" in t: pass\n'
               'doc.pop("partial")\nentry["requirements"] = {"em_lux": 1.0}\n'
               'scene = {"targets": [], "cells": [2, 2]}\n')
    assert sorted(key_reads(ast.parse(planted), result_keys())) == [
        (1, "targets"), (2, "mean_lux"), (3, "verdict"), (4, "partial")]


def test_no_workbench_module_reads_result_keys_by_hand():
    """Results are read through lightsolver_results (lighting.solver.results.read, the results
    object's read(), AnalysisResult): a module that subscripts a results document again reads
    it a second way. Keys the scene format shares (photons, backend, name, ...) cannot be told
    apart by this scan."""
    keys = result_keys()
    found = []
    for path in SOURCES:
        where = str(path.relative_to(WORKBENCH))
        for line, key in key_reads(ast.parse(path.read_text(), str(path)), keys):
            if (where, key) not in NOT_RESULTS:
                found.append(f"{where}:{line}: {key!r}")
    assert not found, "read through lightsolver_results instead: " + ", ".join(found)
