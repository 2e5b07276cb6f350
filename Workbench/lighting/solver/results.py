# SPDX-License-Identifier: LGPL-2.1-or-later
"""Results: the solver's layout as plain data, kept in the document, formatted as a table.

Read through the solver's one Python results reader, ``lightsolver_results``
(NativeSolver/python/lightsolver_results): its per-type reading of each target and its
migration of older results (grid statistics from the cells) are the report's too."""
from __future__ import annotations

import importlib
import json
import math
import os
import sys
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any, Dict, List, Optional, Tuple

READER = "lightsolver_results"


def reader() -> ModuleType:
    """Import ``lightsolver_results``: beside the ``lightsolver`` module (a build folder, the
    folder scripts/install-workbench.sh puts on the path), else in the source tree this
    workbench belongs to. It needs no native module, so stored results read without one."""
    try:
        return importlib.import_module(READER)
    except ImportError:
        pass
    from lighting.messages import SolverUnavailableError
    from lighting.solver import run

    folders = run.candidate_dirs() + [os.path.join(run.repository_root(), "NativeSolver",
                                                   "python")]
    for folder in folders:
        if os.path.isfile(os.path.join(folder, READER, "__init__.py")):
            if folder not in sys.path:
                sys.path.append(folder)
            return importlib.import_module(READER)
    raise SolverUnavailableError(f"The results reader '{READER}' is not found beside the "
                                 f"lightsolver module nor in {folders[-1]}; build the project "
                                 "(cmake --build build)")


def _float(value: Any, default: float = 0.0) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        return default
    return number if math.isfinite(number) else default


#: Grid-cell numpy arrays that ``lightsolver.solve()`` adds beside the results layout.
CELL_ARRAYS = ("cells_lux", "cells_ci_low_lux", "cells_ci_high_lux", "cells_hits")
#: Target types whose result is a UGR (an observer grid's is its maximum).
GLARE_KINDS = ("observer", "observer_grid")


def normalise(raw: Dict[str, Any]) -> Dict[str, Any]:
    """The solver's results as plain JSON data in the ``lightsolver.results/1`` layout.

    ``lightsolver.solve()`` already returns the layout the CLI writes (one C++ serializer,
    docs/schemas/results.schema.json); only the numpy cell arrays it adds beside it are dropped
    (``lightsolver_results.plain``), so results from either source are stored alike."""
    return reader().plain(raw)


@dataclass
class TargetResult:
    """Illuminance on one target (lux); grids add Emin, Emax, U0 and the cells."""

    name: str
    label: str
    kind: str
    mean_lux: float
    ci_low_lux: float
    ci_high_lux: float
    sigma_lux: float = 0.0
    hits: float = 0.0
    area_m2: float = 0.0
    min_lux: Optional[float] = None
    max_lux: Optional[float] = None
    uniformity: Optional[float] = None
    min_ci_lux: Tuple[float, float] = (0.0, 0.0)
    max_ci_lux: Tuple[float, float] = (0.0, 0.0)
    cells_uv: Optional[Tuple[int, int]] = None
    cells_lux: List[float] = field(default_factory=list)
    cells_ci_low_lux: List[float] = field(default_factory=list)
    cells_ci_high_lux: List[float] = field(default_factory=list)
    cells_hits: List[float] = field(default_factory=list)
    required_lux: float = 0.0
    required_uniformity: float = 0.0
    #: The solver's overall verdict on the target's requirements ("pass", "fail",
    #: "undecided"), judged from the intervals; None when it judged none.
    verdict: Optional[str] = None
    #: The solver's verdict per requirement (docs/scene-format.md, "Requirements and verdicts").
    verdicts: Dict[str, Dict[str, Any]] = field(default_factory=dict)
    #: The solver's U0 interval (honest for a minimum over noisy cells), when it gave one.
    solver_uniformity_ci: Optional[Tuple[float, float]] = None
    #: Observers: the UGR (None when no luminaire counts or no reflected light reached the
    #: eye) and its interval (an end None when unbounded), from the traced background
    #: luminance (docs/glare.md).
    ugr: Optional[float] = None
    ugr_ci: Tuple[Optional[float], Optional[float]] = (None, None)

    def ugr_text(self) -> Tuple[str, str]:
        """("UGR 17.2", "16.9-17.5") of an observer; "-" where a value is absent."""
        def show(value: Optional[float]) -> str:
            return "-" if value is None else f"{value:.1f}"

        name = "max UGR" if self.kind == "observer_grid" else "UGR"
        return (f"{name} {show(self.ugr)}", f"{show(self.ugr_ci[0])}-{show(self.ugr_ci[1])}")

    @property
    def uniformity_ci(self) -> Tuple[float, float]:
        """The solver's U0 interval when it judged requirements; otherwise a conservative one
        from the intervals of Emin and Em."""
        if self.solver_uniformity_ci is not None:
            return self.solver_uniformity_ci
        if self.uniformity is None or self.ci_high_lux <= 0.0:
            return (0.0, 0.0)
        low = self.min_ci_lux[0] / self.ci_high_lux
        high = self.min_ci_lux[1] / self.ci_low_lux if self.ci_low_lux > 0 else float("inf")
        return (low, high)

    def verdict_text(self) -> str:
        """"pass", "FAIL" or "undecided" as the solver judged the intervals; for results of
        older versions (no verdicts) the point estimate against the requirement, marked "(est.)";
        "" without requirements."""
        if self.verdict is not None:
            return {"pass": "pass", "fail": "FAIL"}.get(self.verdict, "undecided")
        passed = self.passes()
        return "" if passed is None else ("pass (est.)" if passed else "FAIL (est.)")

    def passes(self) -> Optional[bool]:
        """True/False against RequiredLux/RequiredUniformity from the point estimates; None when
        none is set (the solver's verdicts, from the intervals, are ``verdict``)."""
        checks = []
        if self.required_lux > 0.0:
            checks.append(self.mean_lux >= self.required_lux)
        if self.required_uniformity > 0.0 and self.uniformity is not None:
            checks.append(self.uniformity >= self.required_uniformity)
        return all(checks) if checks else None

    @classmethod
    def from_target(cls, target: Any, label: str = "",
                    required: Tuple[float, float] = (0.0, 0.0)) -> "TargetResult":
        """From a ``lightsolver_results.Target`` (the reader's per-type reading of a migrated
        ``targets[]`` entry)."""
        value = lambda s: _float(s.value) if s is not None else 0.0  # noqa: E731
        result = cls(name=target.name, label=label or target.name, kind=target.type,
                     mean_lux=value(target.em), ci_low_lux=_float(target.em.low),
                     ci_high_lux=_float(target.em.high), sigma_lux=_float(target.sigma_lux),
                     hits=_float(target.hits), area_m2=_float(target.area_m2),
                     required_lux=required[0], required_uniformity=required[1])
        if target.is_glare:  # an observer grid's: the maximum's
            result.ugr = target.ugr.value
            result.ugr_ci = (target.ugr.low, target.ugr.high)
        if target.is_grid:
            cells = target.cells
            result.cells_uv = target.cells_uv
            result.cells_lux = [_float(c.get("lux")) for c in cells]
            result.cells_ci_low_lux = [_float(c.get("ci_low_lux")) for c in cells]
            result.cells_ci_high_lux = [_float(c.get("ci_high_lux")) for c in cells]
            result.cells_hits = [_float(c.get("hits")) for c in cells]
            result.min_lux, result.max_lux = value(target.emin), value(target.emax)
            result.uniformity = value(target.u0)
            if result.cells_lux:  # the extreme cells' own intervals, until the solver's below
                lux, low, high = result.cells_lux, result.cells_ci_low_lux, result.cells_ci_high_lux
                i_min = min(range(len(lux)), key=lux.__getitem__)
                i_max = max(range(len(lux)), key=lux.__getitem__)
                result.min_ci_lux = (low[i_min], high[i_min])
                result.max_ci_lux = (low[i_max], high[i_max])
            if target.emin.has_interval:  # simultaneous over the cells: docs/statistics.md
                result.min_ci_lux = (target.emin.low, target.emin.high)
            if target.emax.has_interval:
                result.max_ci_lux = (target.emax.low, target.emax.high)
            if target.u0.has_interval:
                result.solver_uniformity_ci = (target.u0.low, target.u0.high)
        if target.verdict is not None:
            result.verdict = target.verdict
            result.verdicts = dict(target.verdicts)
        return result

    @classmethod
    def from_entry(cls, entry: Dict[str, Any], label: str = "",
                   required: Tuple[float, float] = (0.0, 0.0)) -> "TargetResult":
        """From one ``targets[]`` entry (migrated alone, as the reader does a whole document)."""
        doc = {"format": reader().FORMAT, "targets": [entry]}
        return cls.from_target(reader().read(doc, strict=False, check_schema=False).targets[0],
                               label, required)


@dataclass
class AnalysisResult:
    """What :func:`lighting.analyze` returns: per-target results and run facts."""

    targets: List[TargetResult]
    photons: float = 0.0
    partial: bool = False
    seconds: float = 0.0
    backend: str = ""
    confidence: float = 0.95
    warnings: List[str] = field(default_factory=list)
    scene_file: str = ""
    results_file: str = ""
    data: Dict[str, Any] = field(default_factory=dict)

    def __getitem__(self, key: str) -> TargetResult:
        """The target with this object name or label."""
        for tgt in self.targets:
            if key in (tgt.name, tgt.label):
                return tgt
        raise KeyError(key)

    def table(self) -> str:
        """The results table as text (see :func:`format_table`)."""
        return format_table(self)

    @classmethod
    def from_data(cls, data: Dict[str, Any], labels: Optional[Dict[str, str]] = None,
                  required: Optional[Dict[str, Tuple[float, float]]] = None,
                  scene_file: str = "", results_file: str = "") -> "AnalysisResult":
        """From a normalised results dictionary."""
        labels = labels or {}
        required = required or {}
        # Not schema-checked here: live frames arrive many times a second, and documents
        # saved by older versions must open; the solver wrote what it checks.
        read = reader().read(data, strict=False, check_schema=False)
        targets = [TargetResult.from_target(t, labels.get(t.name, ""),
                                            required.get(t.name, (0.0, 0.0)))
                   for t in read.targets]
        return cls(targets=targets, photons=_float(data.get("photons")),
                   partial=bool(data.get("partial", False)), seconds=_float(data.get("seconds")),
                   backend=str(data.get("backend", "")),
                   confidence=_float(data.get("confidence"), 0.95),
                   warnings=[str(w) for w in data.get("warnings", [])],
                   scene_file=scene_file, results_file=results_file, data=data)

    def to_json(self) -> str:
        """The results in the CLI's JSON layout."""
        return json.dumps(self.data, indent=1)


def _ci(low: float, high: float) -> str:
    return f"{low:.1f}-{high:.1f}"


def format_table(result: AnalysisResult) -> str:
    """Fixed-width text table: Em, Emin, Emax (lx) and U0 with their confidence intervals."""
    level = f"{result.confidence * 100:g}%"
    header = ("Target", "Type", "Em lx", f"Em {level} CI", "Emin lx", "Emin CI", "Emax lx",
              "Emax CI", "U0", "U0 CI", "Check")
    rows = [header]
    for t in result.targets:
        verdict = t.verdict_text()
        if t.kind == "grid":
            u_lo, u_hi = t.uniformity_ci
            rows.append((t.label, t.kind, f"{t.mean_lux:.1f}", _ci(t.ci_low_lux, t.ci_high_lux),
                         f"{t.min_lux:.1f}", _ci(*t.min_ci_lux), f"{t.max_lux:.1f}",
                         _ci(*t.max_ci_lux), f"{t.uniformity:.2f}", f"{u_lo:.2f}-{u_hi:.2f}",
                         verdict))
        elif t.kind in GLARE_KINDS:
            rows.append((t.label, t.kind, *t.ugr_text(), "-", "-", "-", "-", "-", "-", verdict))
        else:
            rows.append((t.label, t.kind, f"{t.mean_lux:.1f}", _ci(t.ci_low_lux, t.ci_high_lux),
                         "-", "-", "-", "-", "-", "-", verdict))
    widths = [max(len(str(r[i])) for r in rows) for i in range(len(header))]
    lines = ["  ".join(str(c).ljust(w) for c, w in zip(r, widths)).rstrip() for r in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    facts = f"{result.photons:.0f} photons, {result.seconds:.2f} s"
    if result.backend:
        facts += f", backend {result.backend}"
    if result.partial:
        facts += ", PARTIAL (cancelled)"
    lines.append(facts)
    return "\n".join(lines)
