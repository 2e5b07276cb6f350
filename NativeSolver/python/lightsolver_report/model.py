# SPDX-License-Identifier: LGPL-2.1-or-later
"""What the report shows, gathered from the solver boundary only: the scene (docs/scene-format.md)
and the results (docs/schemas/results.schema.json, with the requirements and verdicts of
issue 13 when the solver wrote them). Plain data, no HTML: the templates lay it out."""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

import lightsolver_results
from lightsolver_report.fmt import finite
from lightsolver_report.schedule import (LuminaireRow, MaterialRow, PhotometricFiles,
                                         PhotometryFn, build_luminaires, build_materials)
from lightsolver_results import Stat, Target

#: Verdict keys in the order the report lists them, with the requirement key and unit of each.
QUANTITIES: Tuple[Tuple[str, str, str], ...] = (
    ("em", "em_lux", "lx"), ("emin", "emin_lux", "lx"), ("u0", "u0", ""), ("ud", "ud", ""))


@dataclass
class Verdict:
    """One requirement's verdict, as the solver decided it from the interval."""

    key: str  # em, emin, u0, ud
    verdict: str  # pass, fail, undecided
    value: Optional[float]
    low: Optional[float]
    high: Optional[float]
    required: Optional[float]
    relation: str = ">="
    to_decide_photons: Optional[float] = None
    to_decide_seconds: Optional[float] = None

    @property
    def is_lux(self) -> bool:
        return self.key in ("em", "emin")


@dataclass
class Requirement:
    """One stated requirement (from the results' resolved ``requirements``)."""

    key: str  # em, emin, u0, ud, ugr
    relation: str
    value: float


@dataclass
class GridData:
    """A grid's cells (lux, shape (nv, nu), row iv along edge2) and how to draw them."""

    lux: np.ndarray
    size_u_m: float
    size_v_m: float
    origin_u_m: float = 0.0
    origin_v_m: float = 0.0
    axis_u: str = "u"
    axis_v: str = "v"


@dataclass
class Area:
    """A calculation area (a target) with its statistics, requirements and verdicts."""

    name: str
    label: str
    type: str
    area_m2: Optional[float]
    hits: Optional[int]
    em: Stat
    emin: Optional[Stat] = None
    emax: Optional[Stat] = None
    u0: Optional[Stat] = None
    ud: Optional[Stat] = None
    cells_uv: Optional[Tuple[int, int]] = None
    requirements: List[Requirement] = field(default_factory=list)
    task: Optional[str] = None
    source: Optional[str] = None
    verdict: Optional[str] = None
    verdicts: List[Verdict] = field(default_factory=list)
    grid: Optional[GridData] = None
    #: Observers (eyes for discomfort glare): the UGR with its interval (docs/glare.md); an
    #: observer grid's maximum over its points, the interval simultaneous over them.
    ugr: Optional[Stat] = None
    #: Observer grids: positions, view directions, and where the maximum UGR is.
    observer_positions: int = 0
    observer_directions: int = 0
    max_at: Optional[Tuple[Tuple[float, float, float], Tuple[float, float, float]]] = None
    horizontal: bool = False
    power_density_w_m2: Optional[float] = None
    power_density_w_m2_100lx: Optional[float] = None
    plan_svg: str = ""
    chart_svg: str = ""
    chart_note: str = ""

    @property
    def ugr_name(self) -> str:
        return "max UGR" if self.type == "observer_grid" else "UGR"

    @property
    def undecided(self) -> List[Verdict]:
        return [v for v in self.verdicts if v.verdict == "undecided"]

    @property
    def to_decide(self) -> Optional[Verdict]:
        """The undecided verdict that needs the most photons (with an estimate), or None."""
        known = [v for v in self.undecided if v.to_decide_photons is not None]
        return max(known, key=lambda v: v.to_decide_photons) if known else None


@dataclass
class Report:
    """Everything the report prints."""

    title: str
    subtitle: str
    date: str
    solver_version: str
    scene_file: str
    document_file: str
    generator: str
    run: Dict[str, Any]
    verdict: Optional[str]
    luminaires: List[LuminaireRow]
    materials: List[MaterialRow]
    areas: List[Area]
    warnings: List[str]
    solver_total_flux_lm: Optional[float]
    #: The schedule's flux is the solver's record of what it traced (False: derived from the
    #: scene, for results written before the solver recorded it).
    traced_flux: bool = True

    @property
    def ugr_tables(self) -> List[LuminaireRow]:
        """The schedule's rows whose file has a UGR table, one per file (rows of the same file
        at other fluxes share the table: it is the file's, for the file's own flux)."""
        seen, out = set(), []
        for row in self.luminaires:
            key = tuple(sorted(row.files))
            if row.ugr_table is not None and key not in seen:
                seen.add(key)
                out.append(row)
        return out

    @property
    def total_count(self) -> int:
        return sum(r.count for r in self.luminaires)

    @property
    def total_flux_lm(self) -> float:
        return sum(r.total_flux_lm for r in self.luminaires)

    @property
    def tilted(self) -> bool:
        """Some luminaire's flux has a TILT table's factor other than 1 in it."""
        return any(r.tilt_factor != 1.0 for r in self.luminaires)

    @property
    def dimmed(self) -> bool:
        """Some luminaire is dimmed (rescaled results)."""
        return any(r.dimming != 1.0 for r in self.luminaires)

    @property
    def total_power_w(self) -> Optional[float]:
        """Connected load, only when every luminaire's power is known."""
        if not self.luminaires or any(r.power_w is None for r in self.luminaires):
            return None
        return sum(r.total_power_w for r in self.luminaires)

    @property
    def areas_with_requirements(self) -> List[Area]:
        return [a for a in self.areas if a.requirements or a.verdicts]

    @property
    def verdict_counts(self) -> Dict[str, int]:
        counts = {"pass": 0, "fail": 0, "undecided": 0}
        for area in self.areas:
            for v in area.verdicts:
                counts[v.verdict] = counts.get(v.verdict, 0) + 1
        return counts


def _requirements(req: Optional[Dict[str, Any]]) -> List[Requirement]:
    if not isinstance(req, dict):
        return []
    items = [Requirement(key, ">=", float(req[rkey])) for key, rkey, _ in QUANTITIES
             if finite(req.get(rkey)) is not None]
    if finite(req.get("ugr_max")) is not None:
        items.append(Requirement("ugr", "<=", float(req["ugr_max"])))
    return items


def _verdicts(raw: Any) -> List[Verdict]:
    if not isinstance(raw, dict):
        return []
    found = []
    for key in [k for k, _, _ in QUANTITIES] + sorted(set(raw) - {k for k, _, _ in QUANTITIES}):
        v = raw.get(key)
        if not isinstance(v, dict):
            continue
        decide = v.get("to_decide") if isinstance(v.get("to_decide"), dict) else {}
        found.append(Verdict(key, str(v.get("verdict", "undecided")), finite(v.get("value")),
                             finite(v.get("ci_low")), finite(v.get("ci_high")),
                             finite(v.get("required")), str(v.get("relation", ">=")),
                             finite(decide.get("photons")), finite(decide.get("seconds"))))
    return found


def _axis_name(edge: np.ndarray) -> Optional[int]:
    """The world axis (0, 1, 2) an edge runs along in the positive sense, else None."""
    length = float(np.linalg.norm(edge))
    for axis in range(3):
        if length > 0 and edge[axis] > 0 and abs(edge[axis] - length) <= 1e-9 * length:
            return axis
    return None


def _grid_data(target: Target, scene_target: Dict[str, Any]) -> Optional[GridData]:
    nu, nv = target.cells_uv or (0, 0)
    cells = target.cells
    if nu * nv == 0 or len(cells) != nu * nv:
        return None
    lux = np.array([float(c["lux"]) for c in cells], dtype=float).reshape(nv, nu)
    e1 = np.asarray(scene_target.get("edge1", (1.0, 0.0, 0.0)), dtype=float)
    e2 = np.asarray(scene_target.get("edge2", (0.0, 1.0, 0.0)), dtype=float)
    corner = np.asarray(scene_target.get("corner", (0.0, 0.0, 0.0)), dtype=float)
    grid = GridData(lux, float(np.linalg.norm(e1)), float(np.linalg.norm(e2)))
    a1, a2 = _axis_name(e1), _axis_name(e2)
    if a1 is not None and a2 is not None and a1 != a2:  # axis-parallel: world coordinates
        grid.origin_u_m, grid.origin_v_m = float(corner[a1]), float(corner[a2])
        grid.axis_u, grid.axis_v = "xyz"[a1], "xyz"[a2]
    return grid


def _is_horizontal_up(scene_target: Dict[str, Any]) -> bool:
    e1 = np.asarray(scene_target.get("edge1", (1.0, 0.0, 0.0)), dtype=float)
    e2 = np.asarray(scene_target.get("edge2", (0.0, 1.0, 0.0)), dtype=float)
    n = np.cross(e1, e2)
    norm = float(np.linalg.norm(n))
    return norm > 0 and n[2] / norm > 0.999


def build_area(target: Target, scene_target: Dict[str, Any], labels: Dict[str, str]) -> Area:
    """One calculation area from its results target (lightsolver_results' per-type reading)
    and its scene entry."""
    area = Area(name=target.name, label=labels.get(target.name, target.name), type=target.type,
                area_m2=target.area_m2, hits=target.hits, em=target.em)
    if target.is_grid:
        area.emin, area.emax, area.u0 = target.emin, target.emax, target.u0
        area.ud = target.ud
        area.cells_uv = target.cells_uv
        area.grid = _grid_data(target, scene_target)
        area.horizontal = _is_horizontal_up(scene_target)
    if target.is_glare:
        area.ugr = target.ugr
    grid = target.observer_grid
    if grid is not None:
        area.observer_positions = len(grid.positions)
        area.observer_directions = len(grid.view_directions)
        if grid.max_at is not None:
            area.max_at = (grid.max_position, grid.max_direction)
    req: Optional[Dict[str, Any]] = target.requirements or None
    if req is None:  # a solver that does not resolve them: show what the scene states
        req = scene_target.get("requirements")
    area.requirements = _requirements(req)
    if isinstance(req, dict):
        area.task = str(req["task"]) if req.get("task") else scene_target.get("task")
        area.source = str(req["source"]) if req.get("source") else None
    area.verdicts = _verdicts(target.entry.get("verdicts"))
    verdict = target.entry.get("verdict")
    area.verdict = str(verdict) if isinstance(verdict, str) else None
    return area


# --- the whole report -------------------------------------------------------------------------

def _run_facts(scene: Dict[str, Any], results: Dict[str, Any]) -> Dict[str, Any]:
    settings = scene.get("settings") if isinstance(scene.get("settings"), dict) else {}
    keys = ("photons", "photons_requested", "seed", "confidence", "backend", "seconds",
            "stop_reason", "partial", "ray_segments", "decide", "target_accuracy",
            "accuracy_met", "max_seconds", "capped_paths", "cut_paths")
    run = {k: results.get(k) for k in keys}
    run["max_bounces"] = settings.get("max_bounces", 1000)
    return run


def build_report(scene: Dict[str, Any], results: Dict[str, Any], *, scene_name: str,
                 base_dir: str, date: str, solver_version: str, title: Optional[str] = None,
                 photometry: Optional[PhotometryFn] = None,
                 material_defaults: Optional[Dict[str, Dict[str, Any]]] = None) -> Report:
    """The report's content. ``scene_name`` is printed as the scene file (give a base name so
    that the output does not depend on where the files lie)."""
    meta = scene.get("metadata") if isinstance(scene.get("metadata"), dict) else {}
    labels = meta.get("labels") if isinstance(meta.get("labels"), dict) else {}
    scene_targets = {str(t.get("name")): t for t in scene.get("targets", [])}
    files = PhotometricFiles(base_dir, photometry)
    # Read once: schema-checked, older layouts migrated (the luminaires' flux then derived
    # from the scene), problems and migrations said among the warnings.
    read = lightsolver_results.read(results, scene, files.scene_flux, strict=False)
    doc = read.doc
    areas = [build_area(t, scene_targets.get(t.name, {}), labels) for t in read.targets]
    luminaires = build_luminaires(scene, files, read.luminaires)
    report = Report(
        title=title or str(meta.get("project") or meta.get("title") or meta.get("document")
                           or os.path.splitext(scene_name)[0]),
        subtitle=str(meta.get("description") or ""),
        date=date, solver_version=solver_version, scene_file=scene_name,
        document_file=os.path.basename(str(meta.get("document_file") or "")),
        generator=str(meta.get("generator") or ""),
        run=_run_facts(scene, doc),
        verdict=doc.get("verdict") if isinstance(doc.get("verdict"), str) else None,
        luminaires=luminaires, materials=build_materials(scene, material_defaults), areas=areas,
        warnings=[str(w) for w in doc.get("warnings", [])] + files.warnings + read.notes,
        solver_total_flux_lm=finite(doc.get("total_flux_lm")), traced_flux=read.traced_flux)
    power = report.total_power_w
    for area in areas:
        if power is not None and area.horizontal and area.area_m2:
            area.power_density_w_m2 = power / area.area_m2
            if area.em.value:
                area.power_density_w_m2_100lx = area.power_density_w_m2 / (area.em.value / 100)
    return report
