# SPDX-License-Identifier: LGPL-2.1-or-later
"""The one Python reader of the solver's results (``lightsolver.results/1``,
docs/schemas/results.schema.json): the report (``lightsolver_report``) and the FreeCAD
workbench (``lighting.solver.results``) read results through it instead of parsing by hand.

Three steps, each in one place:

* :func:`plain`: the layout without the numpy arrays ``lightsolver.solve()`` adds beside it;
* :func:`migrate`: results written by older solvers brought to the current layout (every legacy
  fallback lives here, and each one applied is said in the notes it returns);
* :func:`read`: checked against the schema (with ``jsonschema`` where it is installed), migrated,
  and viewed as :class:`Results` with one :class:`Target` per target: the per-type reading
  (grid statistics, an observer's UGR, an observer grid's maximum and points) is here once.

Pure Python (the standard library; ``jsonschema`` optional), importable by FreeCAD's embedded
interpreter: CMake copies this package and the schema beside the ``lightsolver`` module, and
the source tree's copy finds the schema under ``docs/schemas``."""
from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

__all__ = ["FORMAT", "CELL_ARRAYS", "GLARE_KINDS", "READ_TYPES", "ResultsError", "Stat", "Target",
           "LuminaireFlux", "ObserverGridView", "Provenance", "SourceFile", "Results", "plain",
           "schema", "check", "migrate", "read", "load"]

FORMAT = "lightsolver.results/1"
#: Grid-cell numpy arrays that ``lightsolver.solve()`` adds beside the results layout.
CELL_ARRAYS = ("cells_lux", "cells_ci_low_lux", "cells_ci_high_lux", "cells_hits")
#: Target types whose result is a UGR (an observer grid's is its maximum over its points).
GLARE_KINDS = ("observer", "observer_grid")
#: The target types :func:`read` knows the results of (the solver's target type rows); of
#: another type only the illuminance is read, and the notes say so.
READ_TYPES = ("surface", "grid") + GLARE_KINDS
#: Said on every page that prints a flux derived from the scene instead of the traced one.
DERIVED_FLUX_NOTE = ("these results were written before the solver recorded each luminaire's "
                     "traced flux: the flux shown is derived from the scene, without a "
                     "photometric TILT table's factor")

#: Derives a luminaire's emitted flux (lm) from its scene entry, for results without
#: ``luminaires`` (the report passes one that reads the photometric files).
SceneFlux = Callable[[Dict[str, Any]], float]


class ResultsError(ValueError):
    """The document is no results document this reader understands; the message says where."""


# --- the document ---------------------------------------------------------------------------

def plain(raw: Dict[str, Any]) -> Dict[str, Any]:
    """The results as plain JSON data: ``lightsolver.solve()``'s dict without the numpy cell
    arrays it adds beside the layout (the CLI's file is already plain)."""
    out = {key: value for key, value in raw.items() if key != "targets"}
    out["targets"] = [{k: v for k, v in t.items() if k not in CELL_ARRAYS}
                      if isinstance(t, dict) else t for t in raw.get("targets") or []]
    return out


def _schema_path() -> Optional[Path]:
    here = Path(__file__).resolve().parent
    for path in (here / "results.schema.json",  # copied beside it by CMake
                 here.parents[2] / "docs" / "schemas" / "results.schema.json"):  # source tree
        if path.is_file():
            return path
    return None


_SCHEMA: Optional[Dict[str, Any]] = None


def schema() -> Optional[Dict[str, Any]]:
    """docs/schemas/results.schema.json, or None where neither copy is found."""
    global _SCHEMA
    if _SCHEMA is None:
        path = _schema_path()
        if path is not None:
            _SCHEMA = json.loads(path.read_text(encoding="utf-8"))
    return _SCHEMA


def check(doc: Dict[str, Any]) -> List[str]:
    """What in ``doc`` breaks the results schema ("path: message" each; empty: none). Without
    ``jsonschema`` or the schema file, only the format and the targets list are checked."""
    if not isinstance(doc, dict):
        return ["the results are not a JSON object"]
    if doc.get("format") != FORMAT:
        return [f"format: expected {FORMAT!r}, got {doc.get('format')!r}"]
    if not isinstance(doc.get("targets"), list):
        return ["targets: missing or not a list"]
    found = schema()
    try:
        import jsonschema
    except ImportError:
        return []
    if found is None:
        return []
    validator = jsonschema.Draft202012Validator(found)
    return [f"{'/'.join(map(str, e.absolute_path)) or '(top)'}: {e.message}"
            for e in sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path))]


# --- the migration: older results to the current layout --------------------------------------

def _finite(value: Any) -> Optional[float]:
    """A finite number, or None (JSON null, absent, not a number)."""
    if isinstance(value, bool) or value is None:
        return None
    try:
        number = float(value)
    except (TypeError, ValueError):
        return None
    return number if math.isfinite(number) else None


def _migrate_grid(t: Dict[str, Any]) -> bool:
    """Grid statistics that the oldest solvers left out, from the cells: Emin, Emax and U0.
    True when something was added."""
    if t.get("type") != "grid":
        return False
    added = False
    lux = [_finite(c.get("lux")) for c in t.get("cells") or [] if isinstance(c, dict)]
    lux = [v for v in lux if v is not None]
    if lux and "min_lux" not in t:
        t["min_lux"], added = min(lux), True
    if lux and "max_lux" not in t:
        t["max_lux"], added = max(lux), True
    mean = _finite(t.get("mean_lux"))
    if "uniformity" not in t and "min_lux" in t:
        t["uniformity"], added = (t["min_lux"] / mean if mean else 0.0), True
    return added


def _scene_luminaires(scene: Dict[str, Any], groups: List[Dict[str, Any]],
                      scene_flux: SceneFlux) -> List[Dict[str, Any]]:
    """``luminaires`` derived from the scene: each luminaire's flux by ``scene_flux`` (no TILT:
    tilt_factor 1), its group from the results' groups, else its scene ``group``, else itself."""
    group_of = {str(name): str(g.get("name")) for g in groups if isinstance(g, dict)
                for name in g.get("luminaires", [])}
    out = []
    for lum in scene.get("luminaires", []):
        if not isinstance(lum, dict):
            continue
        name = str(lum.get("name", ""))
        flux = float(scene_flux(lum))
        out.append({"name": name, "type": str(lum.get("type", "")),
                    "group": group_of.get(name, str(lum.get("group") or name)),
                    "flux_lm": flux, "tilt_factor": 1.0, "dimming": 1.0,
                    "emitted_flux_lm": flux})
    return out


def migrate(doc: Dict[str, Any], scene: Optional[Dict[str, Any]] = None,
            scene_flux: Optional[SceneFlux] = None) -> Tuple[Dict[str, Any], List[str]]:
    """A copy of ``doc`` in the current layout, and one note per fallback applied (empty for
    results of the current solver). The fallbacks, each for results of older solvers:

    * grids without ``min_lux``/``max_lux``/``uniformity``: from the cells;
    * no ``luminaires``: derived from ``scene`` by ``scene_flux`` (TILT not applied, said in the
      notes); left out without a scene;
    * no ``warnings``/``groups``: empty lists;
    * no ``provenance``: left out (the view's ``provenance`` is None; such results cannot be
      verified against a scene)."""
    out = plain(doc)  # new top level and target dicts: the migration adds keys to these only
    notes: List[str] = []
    if not isinstance(out.get("targets"), list):
        out["targets"] = []
    for key in ("warnings", "groups"):
        if not isinstance(out.get(key), list):
            out[key] = []
    grids = [str(t.get("name", "")) for t in out["targets"] if _migrate_grid(t)]
    if grids:
        notes.append("grid statistics derived from the cells (results of an older solver): "
                     + ", ".join(grids))
    if "luminaires" not in out and scene is not None and scene_flux is not None:
        out["luminaires"] = _scene_luminaires(scene, out["groups"], scene_flux)
        notes.append(DERIVED_FLUX_NOTE)
    return out, notes


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
    return Stat(_finite(entry.get(value)), _finite(entry.get(low)), _finite(entry.get(high)))


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
        ugr=[[_finite(v) for v in row] for row in grid.get("ugr", [])],
        max_at=(int(at["position"]), int(at["direction"])) if isinstance(at, dict) else None)


@dataclass
class Target:
    """One target's results. Every target has ``em`` (its mean illuminance with interval);
    grids add the cells and Emin, Emax, U0, Ud (intervals where the run judged requirements);
    observers the UGR with interval; observer grids their maximum UGR and ``observer_grid``."""

    name: str
    type: str
    entry: Dict[str, Any]  # the migrated results entry
    area_m2: Optional[float]
    hits: Optional[int]
    em: Stat
    sigma_lux: Optional[float] = None
    cells_uv: Optional[Tuple[int, int]] = None
    cells: List[Dict[str, Any]] = field(default_factory=list)
    emin: Optional[Stat] = None
    emax: Optional[Stat] = None
    u0: Optional[Stat] = None
    ud: Optional[Stat] = None
    ugr: Optional[Stat] = None
    observer_grid: Optional[ObserverGridView] = None
    requirements: Dict[str, Any] = field(default_factory=dict)
    verdicts: Dict[str, Dict[str, Any]] = field(default_factory=dict)
    verdict: Optional[str] = None  # pass, fail, undecided; None when nothing was judged

    @property
    def is_grid(self) -> bool:
        return self.type == "grid"

    @property
    def is_glare(self) -> bool:
        return self.type in GLARE_KINDS


def _target(entry: Dict[str, Any]) -> Target:
    """The per-type reading, once: what each target type's results hold."""
    hits = entry.get("hits")
    t = Target(name=str(entry.get("name", "")), type=str(entry.get("type", "surface")),
               entry=entry, area_m2=_finite(entry.get("area_m2")),
               hits=int(hits) if _finite(hits) is not None else None,
               em=_stat(entry, "mean_lux", "ci_low_lux", "ci_high_lux"),
               sigma_lux=_finite(entry.get("sigma_lux")))
    if t.type == "grid":
        uv = entry.get("cells_uv")
        t.cells = [c for c in entry.get("cells") or [] if isinstance(c, dict)]
        t.cells_uv = (int(uv[0]), int(uv[1])) if uv else (len(t.cells), 1)
        t.emin = _stat(entry, "min_lux", "min_ci_low_lux", "min_ci_high_lux")
        t.emax = _stat(entry, "max_lux", "max_ci_low_lux", "max_ci_high_lux")
        t.u0 = _stat(entry, "uniformity", "uniformity_ci_low", "uniformity_ci_high")
        # Ud = Emin/Emax: the solver's value and interval where it judged requirements, else
        # the ratio of the estimates (no interval).
        t.ud = _stat(entry, "ud", "ud_ci_low", "ud_ci_high")
        if t.ud.value is None and t.emin.value is not None and t.emax.value:
            t.ud = Stat(t.emin.value / t.emax.value)
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
class SourceFile:
    """A file the traced scene read (a mesh, a photometric file, the requirements table)."""

    path: str  # as the scene writes it; the requirements table: its file name
    kind: str  # mesh, photometric, requirements table, file
    sha256: str


@dataclass
class Provenance:
    """Where the results come from (results ``provenance``, docs/scene-format.md): the scene's
    content hash (None: a scene built in memory) and files, the solver, build, machine, options
    and time of the run. ``lightsolver.verify_results`` compares it with a scene file."""

    scene_sha256: Optional[str]
    files: List[SourceFile]
    solver_version: str
    source_commit: str
    build_type: str
    backend: str
    device: str
    mpi_ranks: int
    threads: int
    options: Dict[str, Any]
    started_utc: str
    finished_utc: str
    host: str
    command: str


def _provenance(doc: Dict[str, Any]) -> Optional[Provenance]:
    """The document's provenance; None for results written before the solver recorded it."""
    p = doc.get("provenance")
    if not isinstance(p, dict):
        return None
    text = lambda key: str(p.get(key, ""))  # noqa: E731
    return Provenance(
        scene_sha256=str(p["scene_sha256"]) if p.get("scene_sha256") else None,
        files=[SourceFile(str(f.get("path", "")), str(f.get("kind", "")), str(f.get("sha256", "")))
               for f in p.get("files") or [] if isinstance(f, dict)],
        solver_version=text("solver_version"), source_commit=text("source_commit"),
        build_type=text("build_type"), backend=text("backend"), device=text("device"),
        mpi_ranks=int(p.get("mpi_ranks") or 1), threads=int(p.get("threads") or 0),
        options=dict(p.get("options") or {}), started_utc=text("started_utc"),
        finished_utc=text("finished_utc"), host=text("host"), command=text("command"))


@dataclass
class Results:
    """A results document in the current layout (``doc``) and its view."""

    doc: Dict[str, Any]
    targets: List[Target]
    luminaires: List[LuminaireFlux]
    #: The migration's notes: which fallbacks older results needed (empty: none).
    notes: List[str] = field(default_factory=list)
    #: Where they come from; None for results written before provenance was recorded.
    provenance: Optional[Provenance] = None

    @property
    def traced_flux(self) -> bool:
        """The luminaires' flux is the solver's record of what it traced (not derived)."""
        return DERIVED_FLUX_NOTE not in self.notes and "luminaires" in self.doc

    def luminaire(self, name: str) -> Optional[LuminaireFlux]:
        return next((lum for lum in self.luminaires if lum.name == name), None)

    def __getitem__(self, name: str) -> Target:
        for t in self.targets:
            if t.name == name:
                return t
        raise KeyError(name)


def read(source: Union[Dict[str, Any], str, "os.PathLike[str]"],
         scene: Optional[Dict[str, Any]] = None, scene_flux: Optional[SceneFlux] = None, *,
         strict: bool = True, check_schema: bool = True) -> Results:
    """The results of ``source`` (a results dict or file), migrated to the current layout and
    viewed. Checked against the schema after the migration (``check_schema``): with ``strict``
    a document that breaks it raises ResultsError naming the first problems, otherwise they are
    kept in ``notes``. Another ``format`` is always an error."""
    doc = load(source) if not isinstance(source, dict) else source
    if not isinstance(doc, dict) or doc.get("format", None if strict else FORMAT) != FORMAT:
        found = doc.get("format") if isinstance(doc, dict) else type(doc).__name__
        raise ResultsError(f"not a {FORMAT} document (format: {found!r})")
    current, notes = migrate(doc, scene, scene_flux)
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
    return Results(doc=current, targets=[_target(t) for t in current["targets"]
                                         if isinstance(t, dict)],
                   luminaires=luminaires, notes=notes, provenance=_provenance(current))


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
