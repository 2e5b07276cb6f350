# SPDX-License-Identifier: LGPL-2.1-or-later
"""The one Python reader of the solver's results (``lightsolver.results/1``,
docs/schemas/results.schema.json): the report (``lightsolver_report``) and the FreeCAD
workbench (``lighting``) read results through it instead of parsing by hand.

Three steps, each in one place:

* :func:`plain` (``layout.py``): the layout without the numpy arrays ``lightsolver.solve()``
  adds beside it;
* :func:`migrate` (``migration.py``): results written by older solvers brought to the current
  layout (every legacy fallback lives there, and each one applied is said in the notes it
  returns), verdicts estimated on request for targets the solver did not judge;
* :func:`read`: checked against the schema (with ``jsonschema`` where it is installed), migrated,
  and viewed as :class:`Results` with the run's facts and one :class:`Target` per target: the
  per-type reading (grid statistics and cells, an observer's UGR, an observer grid's maximum
  and points, verdicts) is here once.

Pure Python (the standard library; ``jsonschema`` optional), importable by FreeCAD's embedded
interpreter: CMake copies this package and the schema beside the ``lightsolver`` module, and
the source tree's copy finds the schema under ``docs/schemas``."""
from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple, Union

from .layout import (CELL_ARRAYS, FORMAT, GLARE_KINDS, OPTIMIZATION_FORMAT, READ_TYPES,
                     ResultsError, check, finite, plain, schema)
from .provenance import Provenance, SourceFile, read_provenance, without_run_facts
from .sunlight import SunlightExposureView, SunlightPoint, sunlight_view
from .annual import (ANNUAL_FORMAT, AnnualGrid, AnnualResults, check_annual, read_annual,
                     load_hours)
from .migration import (DERIVED_FLUX_NOTE, ESTIMATED_NOTE, Requirements, SceneFlux, _migrate,
                        migrate)

__all__ = ["FORMAT", "OPTIMIZATION_FORMAT", "CELL_ARRAYS", "GLARE_KINDS", "READ_TYPES", "DERIVED_FLUX_NOTE",
           "ESTIMATED_NOTE", "ResultsError", "Stat", "Cells", "DaylightFactorView", "Target", "LuminaireFlux",
           "ObserverGridView", "RunFacts", "Results", "plain", "schema", "check", "migrate",
           "read", "load", "Provenance", "SourceFile", "without_run_facts",
           "SunlightExposureView", "SunlightPoint", "ANNUAL_FORMAT", "AnnualGrid",
           "AnnualResults", "read_annual", "load_hours", "check_annual"]

# --- the view ---------------------------------------------------------------------------------

@dataclass
class Stat:
    """A value with its confidence interval [low, high] where the results give one (None:
    absent, or unbounded for a UGR end)."""

    value: Optional[float]
    low: Optional[float] = None
    high: Optional[float] = None

    @property
    def has_interval(self) -> bool:
        return self.low is not None and self.high is not None


def _stat(entry: Dict[str, Any], value: str, low: str, high: str) -> Stat:
    return Stat(finite(entry.get(value)), finite(entry.get(low)), finite(entry.get(high)))


@dataclass
class Cells:
    """A grid's cells row by row (index = iv * nu + iu): each one's illuminance, interval and
    photon hits (None where the results lack one)."""

    lux: List[Optional[float]] = field(default_factory=list)
    ci_low_lux: List[Optional[float]] = field(default_factory=list)
    ci_high_lux: List[Optional[float]] = field(default_factory=list)
    hits: List[Optional[int]] = field(default_factory=list)

    def __len__(self) -> int:
        return len(self.lux)


def _cells(cells: List[Dict[str, Any]]) -> Cells:
    hits = [finite(c.get("hits")) for c in cells]
    return Cells(lux=[finite(c.get("lux")) for c in cells],
                 ci_low_lux=[finite(c.get("ci_low_lux")) for c in cells],
                 ci_high_lux=[finite(c.get("ci_high_lux")) for c in cells],
                 hits=[None if h is None else int(h) for h in hits])


@dataclass
class ObserverGridView:
    """An observer grid's points (docs/glare.md, "Observer grids"): positions x view
    directions, the UGR of each (None: no glare or unbounded) and where the maximum is."""

    positions: List[Tuple[float, float, float]]
    view_directions: List[Tuple[float, float, float]]
    ugr: List[List[Optional[float]]]  # [position][direction]
    max_at: Optional[Tuple[int, int]] = None  # (position, direction) of the maximum

    @property
    def points(self) -> int:
        return len(self.positions) * len(self.view_directions)

    @property
    def max_position(self) -> Optional[Tuple[float, float, float]]:
        return self.positions[self.max_at[0]] if self.max_at else None

    @property
    def max_direction(self) -> Optional[Tuple[float, float, float]]:
        return self.view_directions[self.max_at[1]] if self.max_at else None


def _observer_grid(entry: Dict[str, Any]) -> Optional[ObserverGridView]:
    grid = entry.get("observer_grid")
    if not isinstance(grid, dict):
        return None
    vec = lambda p: tuple(float(x) for x in p)  # noqa: E731
    at = grid.get("max_at")
    return ObserverGridView(
        positions=[vec(p) for p in grid.get("positions", [])],
        view_directions=[vec(d) for d in grid.get("view_directions", [])],
        ugr=[[finite(v) for v in row] for row in grid.get("ugr", [])],
        max_at=(int(at["position"]), int(at["direction"])) if isinstance(at, dict) else None)


@dataclass
class DaylightFactorView:
    """A daylight-factor grid's daylight factor in percent (docs/daylight.md, "Daylight factor
    and EN 17037"): the sky it is of, that sky's outside illuminance, the grid's mean, its
    smallest cell and the values reached over 50 % and 95 % of its area (each with its
    interval), and every cell's value row by row."""

    sky: str
    outside_illuminance_lx: Optional[float]
    mean: Stat
    min: Stat
    p50: Stat
    p95: Stat
    cells: List[Optional[float]] = field(default_factory=list)


def _daylight_factor(entry: Dict[str, Any]) -> Optional[DaylightFactorView]:
    df = entry.get("daylight_factor")
    if not isinstance(df, dict):
        return None
    return DaylightFactorView(
        sky=str(df.get("sky", "")), outside_illuminance_lx=finite(df.get("outside_illuminance_lx")),
        mean=_stat(df, "mean_percent", "ci_low_percent", "ci_high_percent"),
        min=_stat(df, "min_percent", "min_ci_low_percent", "min_ci_high_percent"),
        p50=_stat(df, "p50_percent", "p50_ci_low_percent", "p50_ci_high_percent"),
        p95=_stat(df, "p95_percent", "p95_ci_low_percent", "p95_ci_high_percent"),
        cells=[finite(c.get("percent")) for c in df.get("cells") or [] if isinstance(c, dict)])


@dataclass
class Target:
    """One target's results. Every target has ``em`` (its mean illuminance with interval);
    grids add the cells (``cells`` as entries, ``cell_values`` as lists) and Emin, Emax, U0,
    Ud (intervals where the run judged requirements); observers the UGR with interval;
    observer grids their maximum UGR and ``observer_grid``. A target with requirements has
    their ``verdicts`` and the overall ``verdict``: the solver's, judged from the intervals, or
    where ``estimated`` the migration's from the point estimates (:func:`migrate`)."""

    name: str
    type: str
    entry: Dict[str, Any]  # the migrated results entry
    area_m2: Optional[float]
    hits: Optional[int]
    em: Stat
    sigma_lux: Optional[float] = None
    cells_uv: Optional[Tuple[int, int]] = None
    cells: List[Dict[str, Any]] = field(default_factory=list)
    cell_values: Cells = field(default_factory=Cells)
    emin: Optional[Stat] = None
    emax: Optional[Stat] = None
    u0: Optional[Stat] = None
    ud: Optional[Stat] = None
    ugr: Optional[Stat] = None
    observer_grid: Optional[ObserverGridView] = None
    daylight_factor: Optional[DaylightFactorView] = None  # daylight-factor grids
    requirements: Dict[str, Any] = field(default_factory=dict)
    verdicts: Dict[str, Dict[str, Any]] = field(default_factory=dict)
    verdict: Optional[str] = None  # pass, fail, undecided; None when nothing was judged
    estimated: bool = False  # the verdicts are point estimates (never undecided), not judged

    def verdict_of(self, name: str) -> Optional[str]:
        """The verdict on one requirement ("em", "u0", "emin", "ud", "ugr"; a daylight-factor
        grid's "df_target", "df_minimum"), or None when it was not judged."""
        found = self.verdicts.get(name, {}).get("verdict")
        return str(found) if found in ("pass", "fail", "undecided") else None

    def to_decide(self, name: str) -> Tuple[Optional[int], Optional[float]]:
        """What deciding an undecided requirement would cost: (photons of a whole run, tracing
        seconds), an element None when unknown (the value on the bound: no run decides it);
        (None, None) for a requirement that is not undecided (docs/statistics.md)."""
        cost = self.verdicts.get(name, {}).get("to_decide") or {}
        photons, seconds = finite(cost.get("photons")), finite(cost.get("seconds"))
        return (int(photons) if photons is not None else None, seconds)

    @property
    def is_grid(self) -> bool:
        return self.type == "grid"

    @property
    def is_glare(self) -> bool:
        return self.type in GLARE_KINDS


def _target(entry: Dict[str, Any], estimated: bool = False) -> Target:
    """The per-type reading, once: what each target type's results hold."""
    hits = entry.get("hits")
    t = Target(name=str(entry.get("name", "")), type=str(entry.get("type", "surface")),
               entry=entry, area_m2=finite(entry.get("area_m2")),
               hits=int(hits) if finite(hits) is not None else None,
               em=_stat(entry, "mean_lux", "ci_low_lux", "ci_high_lux"),
               sigma_lux=finite(entry.get("sigma_lux")))
    if t.type == "grid":
        uv = entry.get("cells_uv")
        t.cells = [c for c in entry.get("cells") or [] if isinstance(c, dict)]
        t.cells_uv = (int(uv[0]), int(uv[1])) if uv else (len(t.cells), 1)
        t.cell_values = _cells(t.cells)
        t.emin = _stat(entry, "min_lux", "min_ci_low_lux", "min_ci_high_lux")
        t.emax = _stat(entry, "max_lux", "max_ci_low_lux", "max_ci_high_lux")
        t.u0 = _stat(entry, "uniformity", "uniformity_ci_low", "uniformity_ci_high")
        # Ud = Emin/Emax: the solver's value and interval where it judged requirements, else
        # the ratio of the estimates (no interval).
        t.ud = _stat(entry, "ud", "ud_ci_low", "ud_ci_high")
        if t.ud.value is None and t.emin.value is not None and t.emax.value:
            t.ud = Stat(t.emin.value / t.emax.value)
        t.daylight_factor = _daylight_factor(entry)
    if t.type in GLARE_KINDS:  # an observer grid's: the maximum's
        t.ugr = _stat(entry, "ugr", "ugr_ci_low", "ugr_ci_high")
    if t.type == "observer_grid":
        t.observer_grid = _observer_grid(entry)
    if isinstance(entry.get("requirements"), dict):
        t.requirements = dict(entry["requirements"])
    if entry.get("verdict") in ("pass", "fail", "undecided"):
        t.verdict = str(entry["verdict"])
        t.verdicts = {k: v for k, v in (entry.get("verdicts") or {}).items()
                      if isinstance(v, dict)}
        t.estimated = estimated
    return t


@dataclass
class LuminaireFlux:
    """One luminaire as traced (results ``luminaires``): the flux it emitted in the
    calculation, after TILT and a rescale's dimming."""

    name: str
    type: str
    group: str
    flux_lm: float
    tilt_factor: float
    dimming: float
    emitted_flux_lm: float


@dataclass
class RunFacts:
    """What the run did (the results' top level): photons traced and asked for, whether it was
    cancelled (``partial``) and why it stopped, time, backend, the intervals' confidence and the
    seed, its warnings, and whether it traced until every verdict was decided (``decide``)."""

    photons: int = 0
    photons_requested: Optional[int] = None
    partial: bool = False
    stop_reason: Optional[str] = None
    seconds: float = 0.0
    backend: str = ""
    confidence: Optional[float] = None
    seed: Optional[int] = None
    warnings: List[str] = field(default_factory=list)
    decide: bool = False
    accuracy_met: Optional[bool] = None


def _run(doc: Dict[str, Any]) -> RunFacts:
    count = lambda key: None if finite(doc.get(key)) is None else int(doc[key])  # noqa: E731
    met = doc.get("accuracy_met")
    return RunFacts(photons=count("photons") or 0, photons_requested=count("photons_requested"),
                    partial=doc.get("partial") is True,
                    stop_reason=str(doc["stop_reason"]) if doc.get("stop_reason") else None,
                    seconds=finite(doc.get("seconds")) or 0.0,
                    backend=str(doc.get("backend") or ""),
                    confidence=finite(doc.get("confidence")), seed=count("seed"),
                    warnings=[str(w) for w in doc.get("warnings") or []],
                    decide=doc.get("decide") is True,
                    accuracy_met=met if isinstance(met, bool) else None)


@dataclass
class Results:
    """A results document in the current layout (``doc``) and its view: the run's facts, one
    :class:`Target` per target, the traced luminaires and the overall verdict."""

    doc: Dict[str, Any]
    targets: List[Target]
    luminaires: List[LuminaireFlux]
    #: The migration's notes: which fallbacks older results needed (empty: none).
    notes: List[str] = field(default_factory=list)
    run: RunFacts = field(default_factory=RunFacts)
    #: The solver's verdict over every target it judged (fail if any fails, else undecided if
    #: any is, else pass); None when it judged none. Estimated verdicts never enter it.
    verdict: Optional[str] = None
    #: Where they come from; None for results written before provenance was recorded.
    provenance: Optional[Provenance] = None

    @property
    def has_contributions(self) -> bool:
        """Each control group's part is in the results (groups and every target's
        contributions): what a rescale to other dimming levels needs."""
        return bool(self.doc.get("groups")) and any(
            "contributions" in t.entry for t in self.targets)

    @property
    def traced_flux(self) -> bool:
        """The luminaires' flux is the solver's record of what it traced (not derived)."""
        return DERIVED_FLUX_NOTE not in self.notes and "luminaires" in self.doc

    @property
    def rescaled(self) -> Dict[str, float]:
        """Each group's factor against the flux it was traced at, where the results are the
        same trace with other group fluxes (a rescale, results combined from group traces);
        empty for results as traced."""
        factors = self.doc.get("rescaled")
        return {str(k): float(v) for k, v in factors.items()} if isinstance(factors, dict) else {}

    @property
    def sunlight_exposure(self) -> Optional[SunlightExposureView]:
        """EN 17037 sunlight exposure at the scene's reference points; None without it."""
        return sunlight_view(self.doc)

    def luminaire(self, name: str) -> Optional[LuminaireFlux]:
        return next((lum for lum in self.luminaires if lum.name == name), None)

    def __getitem__(self, name: str) -> Target:
        for t in self.targets:
            if t.name == name:
                return t
        raise KeyError(name)


def read(source: Union[Dict[str, Any], str, "os.PathLike[str]"],
         scene: Optional[Dict[str, Any]] = None, scene_flux: Optional[SceneFlux] = None, *,
         strict: bool = True, check_schema: bool = True,
         requirements: Optional[Requirements] = None) -> Results:
    """The results of ``source`` (a results dict or file), migrated to the current layout and
    viewed. Checked against the schema after the migration (``check_schema``): with ``strict``
    a document that breaks it raises ResultsError naming the first problems, otherwise they are
    kept in ``notes``. Another ``format`` is always an error. ``requirements`` (by target name,
    scene-file keys): judged on the point estimates of the targets the solver did not judge
    (:func:`migrate`; their ``estimated`` is set)."""
    doc = load(source) if not isinstance(source, dict) else source
    if isinstance(doc, dict) and doc.get("format") == OPTIMIZATION_FORMAT:
        raise ResultsError(f"an optimizer's output ({OPTIMIZATION_FORMAT}), not results: it holds "
                           "configurations, not their light; trace the chosen configuration's "
                           "scene for its results")
    if not isinstance(doc, dict) or doc.get("format", None if strict else FORMAT) != FORMAT:
        found = doc.get("format") if isinstance(doc, dict) else type(doc).__name__
        raise ResultsError(f"not a {FORMAT} document (format: {found!r})")
    current, notes, estimated = _migrate(doc, scene, scene_flux, requirements)
    problems = check(dict(current, format=FORMAT)) if check_schema else []
    if problems and strict:
        raise ResultsError("the results break docs/schemas/results.schema.json: "
                           + "; ".join(problems[:5]))
    notes.extend(f"schema: {p}" for p in problems)
    notes.extend(f"target {t.get('name')!r}: type {t.get('type')!r} is unknown to this reader; "
                 "only its illuminance is read" for t in current["targets"]
                 if isinstance(t, dict) and t.get("type", "surface") not in READ_TYPES)
    luminaires = [LuminaireFlux(str(lum["name"]), str(lum["type"]), str(lum["group"]),
                                float(lum["flux_lm"]), float(lum["tilt_factor"]),
                                float(lum["dimming"]), float(lum["emitted_flux_lm"]))
                  for lum in current.get("luminaires", []) if isinstance(lum, dict)]
    targets = [_target(t, str(t.get("name", "")) in estimated) for t in current["targets"]
               if isinstance(t, dict)]
    verdict = current.get("verdict")
    return Results(doc=current, targets=targets, luminaires=luminaires, notes=notes,
                   run=_run(current), provenance=read_provenance(current),
                   verdict=str(verdict) if verdict in ("pass", "fail", "undecided") else None)


def load(path: Union[str, "os.PathLike[str]"]) -> Dict[str, Any]:
    """A results file as a dict; ResultsError naming the file otherwise."""
    try:
        with open(path, encoding="utf-8") as handle:
            data = json.load(handle)
    except (OSError, ValueError) as exc:
        raise ResultsError(f"{path}: cannot read the results: {exc}") from exc
    if not isinstance(data, dict):
        raise ResultsError(f"{path}: the results are not a JSON object")
    return data
