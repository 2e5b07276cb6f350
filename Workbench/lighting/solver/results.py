# SPDX-License-Identifier: LGPL-2.1-or-later
"""Results: the solver's layout as plain data, kept in the document, formatted as a table.

Read through the solver's one Python results reader, ``lightsolver_results``
(NativeSolver/python/lightsolver_results): its per-type reading of each target, its run facts
and its migration of older results (grid statistics from the cells; verdicts on the point
estimates, marked "(est.)", for targets the solver did not judge) are the report's too. No
workbench module reads a results document's keys itself (Tests/python/test_workbench_sources.py
checks it): they read the reader's typed objects, through :func:`read` or the tables here."""
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


def normalise(raw: Dict[str, Any]) -> Dict[str, Any]:
    """The solver's results as plain JSON data in the ``lightsolver.results/1`` layout.

    ``lightsolver.solve()`` already returns the layout the CLI writes (one C++ serializer,
    docs/schemas/results.schema.json); only the numpy cell arrays it adds beside it are dropped
    (``lightsolver_results.plain``), so results from either source are stored alike."""
    return reader().plain(raw)


#: Requirements by target name with the scene file's keys (``em_lux``, ``u0``): what the
#: reader judges on the point estimates of targets its results did not judge.
Requirements = Dict[str, Dict[str, float]]


def read(data: Dict[str, Any], requirements: Optional[Requirements] = None) -> Any:
    """``data`` (a results document) read by ``lightsolver_results``: its typed
    ``Results``, older layouts migrated, and with ``requirements`` the targets the solver did
    not judge judged on their point estimates (``Target.estimated``). Not schema-checked: live
    frames arrive many times a second, and documents saved by older versions must open; the
    solver wrote what it checks. Raises ValueError (``ResultsError``) for no results document."""
    return reader().read(data, strict=False, check_schema=False, requirements=requirements)


def _pair(stat: Any) -> Optional[Tuple[float, float]]:
    """A statistic's interval, or None where the solver gave none."""
    return (float(stat.low), float(stat.high)) if stat is not None and stat.has_interval \
        else None


@dataclass
class TargetResult:
    """Illuminance on one target (lux); grids add Emin, Emax, U0 and the cells. A table row of
    the reader's ``lightsolver_results.Target``: intervals only where the solver gave them."""

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
    #: The solver's intervals of Emin, Emax and U0 (honest for a minimum over noisy cells,
    #: docs/statistics.md): given in runs that judge requirements, else None.
    min_ci_lux: Optional[Tuple[float, float]] = None
    max_ci_lux: Optional[Tuple[float, float]] = None
    uniformity_ci: Optional[Tuple[float, float]] = None
    cells_uv: Optional[Tuple[int, int]] = None
    cells_lux: List[float] = field(default_factory=list)
    cells_ci_low_lux: List[float] = field(default_factory=list)
    cells_ci_high_lux: List[float] = field(default_factory=list)
    cells_hits: List[float] = field(default_factory=list)
    #: The requirements judged (Em and U0; 0 where none), as the verdicts state them.
    required_lux: float = 0.0
    required_uniformity: float = 0.0
    #: The overall verdict on the target's requirements ("pass", "fail", "undecided"); None
    #: when none was judged.
    verdict: Optional[str] = None
    #: The verdict per requirement (docs/scene-format.md, "Requirements and verdicts").
    verdicts: Dict[str, Dict[str, Any]] = field(default_factory=dict)
    #: The verdicts are the reader's point estimates (results without the solver's verdicts
    #: for this target), not the solver's from the intervals.
    estimated: bool = False
    #: The requirements ("em", "u0", ...) the solver left undecided (their ``verdicts`` entry
    #: holds ``to_decide``: what deciding would cost).
    undecided: List[str] = field(default_factory=list)
    #: The verdict per requirement as the reader gives it ("pass", "fail", "undecided").
    verdict_of: Dict[str, str] = field(default_factory=dict)
    #: What deciding each undecided requirement would cost: (photons, seconds), None where
    #: unknown (the reader's ``Target.to_decide``).
    to_decide: Dict[str, Tuple[Optional[int], Optional[float]]] = field(default_factory=dict)
    is_glare: bool = False
    #: Observers: the UGR (None when no luminaire counts or no reflected light reached the
    #: eye) and its interval (an end None when unbounded), from the traced background
    #: luminance (docs/glare.md).
    ugr: Optional[float] = None
    ugr_ci: Tuple[Optional[float], Optional[float]] = (None, None)
    #: A daylight-factor grid's daylight factor (the reader's ``DaylightFactorView``,
    #: docs/scene-format.md, "Results") and its requirements echo (EN 17037 level, median
    #: diffuse illuminance, D_T, D_TM); None / {} for other targets.
    daylight_factor: Optional[Any] = None
    daylight_requirements: Dict[str, Any] = field(default_factory=dict)

    def ugr_text(self) -> Tuple[str, str]:
        """("UGR 17.2", "16.9-17.5") of an observer; "-" where a value is absent."""
        def show(value: Optional[float]) -> str:
            return "-" if value is None else f"{value:.1f}"

        name = "max UGR" if self.kind == "observer_grid" else "UGR"
        return (f"{name} {show(self.ugr)}", f"{show(self.ugr_ci[0])}-{show(self.ugr_ci[1])}")

    def verdict_text(self) -> str:
        """"pass", "FAIL" or "undecided" as the solver judged the intervals; for results without
        the solver's verdicts the point estimate against the requirement, marked "(est.)"; ""
        without requirements."""
        if self.verdict is None:
            return ""
        word = {"pass": "pass", "fail": "FAIL"}.get(self.verdict, "undecided")
        return f"{word} (est.)" if self.estimated else word

    @classmethod
    def from_target(cls, target: Any, label: str = "") -> "TargetResult":
        """From a ``lightsolver_results.Target`` (the reader's per-type reading of a migrated
        ``targets[]`` entry)."""
        value = lambda s: _float(s.value) if s is not None else 0.0  # noqa: E731
        wanted = target.requirements
        result = cls(name=target.name, label=label or target.name, kind=target.type,
                     mean_lux=value(target.em), ci_low_lux=_float(target.em.low),
                     ci_high_lux=_float(target.em.high), sigma_lux=_float(target.sigma_lux),
                     hits=_float(target.hits), area_m2=_float(target.area_m2),
                     required_lux=_float(wanted.get("em_lux")),
                     required_uniformity=_float(wanted.get("u0")), verdict=target.verdict,
                     verdicts=dict(target.verdicts), estimated=target.estimated,
                     undecided=[k for k in target.verdicts
                                if target.verdict_of(k) == "undecided"],
                     to_decide={k: target.to_decide(k) for k in target.verdicts
                                if target.verdict_of(k) == "undecided"},
                     verdict_of={k: str(target.verdict_of(k)) for k in target.verdicts},
                     is_glare=target.is_glare)
        if target.daylight_factor is not None:  # a DF grid's daylight factor, as read
            result.daylight_factor = target.daylight_factor
            result.daylight_requirements = dict(wanted)
        if target.is_glare:  # an observer grid's: the maximum's
            result.ugr = target.ugr.value
            result.ugr_ci = (target.ugr.low, target.ugr.high)
        if target.is_grid:
            cells = target.cell_values
            result.cells_uv = target.cells_uv
            result.cells_lux = [_float(v) for v in cells.lux]
            result.cells_ci_low_lux = [_float(v) for v in cells.ci_low_lux]
            result.cells_ci_high_lux = [_float(v) for v in cells.ci_high_lux]
            result.cells_hits = [_float(v) for v in cells.hits]
            result.min_lux, result.max_lux = value(target.emin), value(target.emax)
            result.uniformity = value(target.u0)
            result.min_ci_lux, result.max_ci_lux = _pair(target.emin), _pair(target.emax)
            result.uniformity_ci = _pair(target.u0)
        return result


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
    #: Why the run stopped ("photons", "accuracy", "decided", ...; "" when not said).
    stop_reason: str = ""
    #: The solver's overall verdict over the targets it judged; None when it judged none.
    verdict: Optional[str] = None
    #: The photons the run was allowed (its budget: a decide run or an accuracy goal may
    #: stop before it); 0 when the results do not say.
    photons_requested: float = 0.0
    #: EN 17037 sunlight exposure (the reader's ``SunlightExposureView``); None without it.
    sunlight: Optional[Any] = None

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
                  requirements: Optional[Requirements] = None, scene_file: str = "",
                  results_file: str = "") -> "AnalysisResult":
        """From a normalised results dictionary, read by the reader (:func:`read`):
        ``requirements`` are judged on the estimates of the targets the solver did not judge."""
        return cls.from_read(read(data, requirements), labels, scene_file, results_file,
                             data)

    @classmethod
    def from_read(cls, found: Any, labels: Optional[Dict[str, str]] = None,
                  scene_file: str = "", results_file: str = "",
                  data: Optional[Dict[str, Any]] = None) -> "AnalysisResult":
        """From the reader's ``lightsolver_results.Results``; ``data``: the document as stored
        (default: the migrated one)."""
        labels = labels or {}
        run = found.run
        result = cls(targets=[TargetResult.from_target(t, labels.get(t.name, ""))
                              for t in found.targets],
                     photons=float(run.photons), partial=run.partial, seconds=run.seconds,
                     backend=run.backend,
                     confidence=run.confidence if run.confidence is not None else 0.95,
                     warnings=list(run.warnings), scene_file=scene_file,
                     results_file=results_file, data=data if data is not None else found.doc,
                     stop_reason=run.stop_reason or "", verdict=found.verdict,
                     photons_requested=_float(run.photons_requested),
                     sunlight=getattr(found, "sunlight_exposure", None))
        return result

    def to_json(self) -> str:
        """The results in the CLI's JSON layout."""
        return json.dumps(self.data, indent=1)


def interval_text(pair: Optional[Tuple[float, float]], digits: int = 1, dash: str = "-") -> str:
    """An interval as "low-high"; "-" where the solver gave none (a run without requirements
    has no Emin, Emax and U0 intervals: docs/statistics.md, "Emin over noisy cells")."""
    return "-" if pair is None else f"{pair[0]:.{digits}f}{dash}{pair[1]:.{digits}f}"


_ci = interval_text


def _df_ci(stat: Any) -> str:
    return _ci((float(stat.low), float(stat.high)), 2) if stat.has_interval else "-"


def value_header(result: AnalysisResult, grid_lux: bool = True) -> str:
    """The value column's header, right for the rows under it: "Em lx" for illuminance only,
    else the kinds present ("Em lx / DF %", "UGR", ...). ``grid_lux``: a DF grid's row shows
    its lux too (the text table) rather than its DF only (the panel)."""
    kinds = []
    for t in result.targets:
        if t.is_glare:
            kinds.append("UGR")
        elif t.daylight_factor is not None:
            kinds += ["Em lx", "DF %"] if grid_lux else ["DF %"]
        else:
            kinds.append("Em lx")
    present = [k for k in ("Em lx", "DF %", "UGR") if k in kinds]
    return " / ".join(present) or "Em lx"


def sunlight_lines(view: Optional[Any]) -> List[str]:
    """EN 17037 sunlight exposure, a line per window ("Window: 3 h 12 min, medium") under a
    title with the day and the minimum solar altitude; [] without it (``view``: the reader's
    ``SunlightExposureView``)."""
    if view is None:
        return []
    altitude = (f", sun above {view.min_elevation_deg:g}°"
                if view.min_elevation_deg is not None else "")
    lines = [f"Sunlight exposure (EN 17037), {view.date}{altitude}:"]
    for point in view.points:
        level = "none (under 1.5 h)" if point.level == "none" else point.level
        lines.append(f"{point.name}: {point.duration_text()}, {level}")
    return lines


def format_table(result: AnalysisResult) -> str:
    """Fixed-width text table: Em, Emin, Emax (lx) and U0 with their confidence intervals (a
    DF grid adds its DF row, an observer its UGR), then the sunlight exposure per window."""
    level = f"{result.confidence * 100:g}%"
    header = ("Target", "Type", value_header(result), f"Em {level} CI", "Emin lx", "Emin CI",
              "Emax lx", "Emax CI", "U0", "U0 CI", "Check")
    rows = [header]
    for t in result.targets:
        verdict = t.verdict_text()
        em_ci = _ci((t.ci_low_lux, t.ci_high_lux))
        if t.kind == "grid":
            rows.append((t.label, t.kind, f"{t.mean_lux:.1f}", em_ci, f"{t.min_lux:.1f}",
                         _ci(t.min_ci_lux), f"{t.max_lux:.1f}", _ci(t.max_ci_lux),
                         f"{t.uniformity:.2f}", _ci(t.uniformity_ci, 2), verdict))
            if t.daylight_factor is not None:  # its DF: mean and minimum in %
                df = t.daylight_factor
                rows.append((t.label, "DF %", f"{float(df.mean.value or 0.0):.2f}",
                             _df_ci(df.mean), f"{float(df.min.value or 0.0):.2f}",
                             _df_ci(df.min),
                             "-", "-", "-", "-", verdict))
        elif t.is_glare:
            rows.append((t.label, t.kind, *t.ugr_text(), "-", "-", "-", "-", "-", "-", verdict))
        else:
            rows.append((t.label, t.kind, f"{t.mean_lux:.1f}", em_ci, "-", "-", "-", "-", "-",
                         "-", verdict))
    widths = [max(len(str(r[i])) for r in rows) for i in range(len(header))]
    lines = ["  ".join(str(c).ljust(w) for c, w in zip(r, widths)).rstrip() for r in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    lines += sunlight_lines(result.sunlight)
    facts = f"{result.photons:.0f} photons, {result.seconds:.2f} s"
    if result.backend:
        facts += f", backend {result.backend}"
    if result.partial:
        facts += ", PARTIAL (cancelled)"
    lines.append(facts)
    return "\n".join(lines)
