# SPDX-License-Identifier: LGPL-2.1-or-later
"""Inverse design from the document: where should the luminaires of the placement domains go?

Each placement domain with a ``Template`` luminaire places up to ``MaxLuminaires`` luminaires:
the template itself and copies of it, each a ``position`` variable (docs/optimization.md §10)
on the domain's candidate lattice (``placement_domain.optimization_rectangle``), never two in
one place. The exported scene gets the copies, the ``optimization`` block is built from the
intention (by default what the target requires: docs/optimization.md §12), and
``lightsolver.optimize`` returns the set of statistically indistinguishable optimal
configurations (ISOC). :meth:`PlacementResult.apply` leaves exactly the chosen layout's
luminaires for the domains, in one undo step."""
from __future__ import annotations

import copy
import os
import re
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import FreeCAD

from lighting.messages import CheckError, Report, SolverError
from lighting.objects import analysis as analysis_mod
from lighting.objects import placement_domain as domain_mod
from lighting.units import MM_TO_M

GOALS = ("minimize_installed_flux", "maximize_uniformity", "maximize_mean_illuminance",
         "minimize_mean_illuminance")
COPY_SUFFIX = "_copy"
_COPY_RE = r"{}{}(\d+)$"
# A luminaire "sits on" a domain's face when its anchor is this close to the face (mm), beyond
# the mounting offset: the office's ceiling panels hang 50 mm under the slab.
ON_FACE_TOLERANCE_MM = 200.0


@dataclass
class Placement:
    """One luminaire the optimizer places: its scene name, template and domain, and its
    document object when it has one (the template, or a copy made by an earlier apply()).
    ``optional``: beyond the domain's MinLuminaires, so the search may leave it out (its flux
    is a variable with levels 0 and the template's flux) when minimising the installed flux."""

    name: str
    template: Any
    domain: Any
    obj: Optional[Any] = None
    label: str = ""
    optional: bool = False


@dataclass
class PlacementResult:
    """The optimizer's answer: ISOC members, best first (format lightsolver.optimization/1).

    ``removed``: luminaires apply() deletes - copies the domain no longer needs and, if the
    caller asked for it (``replace_others``), other luminaires on a domain's face."""

    raw: Dict[str, Any]
    placements: List[Placement]
    scene_file: str
    doc: Any = None
    report: Report = field(default_factory=Report)
    removed: List[Any] = field(default_factory=list)

    @property
    def members(self) -> List[Dict[str, Any]]:
        """Distinct optima, best first: ``positions_m`` (luminaire name -> [x, y, z], only the
        luminaires the optimum installs), ``count``, ``mean``, ``ci`` and ``constraints``
        (constraint means: Em, U0 for the requirement intentions). Members that differ only in
        where a left-out luminaire would have been, or by swapping luminaires, are one layout;
        among equal objectives (installed flux is exact) the one that exceeds the requirements
        most comes first."""
        out, seen = [], set()
        for rank, m in enumerate(self.raw["isoc"]):
            scene, obj = m["scene"], m["objective"]
            placed = {p.name: scene[p.name] for p in self.placements if _installed(scene, p)}
            layout = tuple(sorted(tuple(round(c, 6) for c in xyz) for xyz in placed.values()))
            if layout in seen:
                continue
            seen.add(layout)
            means = [c["mean"] for c in m.get("constraints", [])]
            out.append({"positions_m": placed, "count": len(placed), "mean": obj["mean"],
                        "ci": (obj["ci_low"], obj["ci_high"]), "constraints": means,
                        "_key": (obj["mean"], -sum(means), rank)})
        maximize = self.raw.get("goal", "maximize") == "maximize"
        out.sort(key=lambda m: ((-1 if maximize else 1) * m["_key"][0],) + m["_key"][1:])
        for m in out:
            del m["_key"]
        return out

    def apply(self, member: int = 0) -> List[Any]:
        """Leave exactly optimum ``member``'s luminaires for the domains, in one undo step:
        move the template, move or create the copies it installs, delete the copies it leaves
        out and the luminaires in ``removed``. Returns the luminaires placed."""
        chosen = self.members[member]["positions_m"]
        self.doc.openTransaction("Apply optimized placement")
        try:
            placed = []
            for p in self.placements:
                if p.name not in chosen:
                    if p.obj is not None and p.obj is not p.template:
                        self.doc.removeObject(p.obj.Name)
                    p.obj = None
                    continue
                if p.obj is None:
                    p.obj = _new_copy(p)
                _move_to(p.obj, chosen[p.name])
                placed.append(p.obj)
            for obj in self.removed:
                if self.doc.getObject(obj.Name) is not None:
                    self.doc.removeObject(obj.Name)
            self.removed = []
            _renumber_copies(self.placements)
            self.doc.recompute()
        finally:
            self.doc.commitTransaction()
        return placed


def _installed(scene: Dict[str, Any], p: Placement) -> bool:
    """False when the optimum sets this luminaire's flux to 0 (leaves it out)."""
    flux = scene.get(f"{p.name}.flux_lm")
    return flux is None or flux[0] > 0.0


def _new_copy(p: Placement) -> Any:
    """A copy of the template, labelled so the next optimization finds and reuses it, in the
    template's analyses."""
    obj = p.template.Document.copyObject(p.template)
    obj.Label = p.label
    for parent in p.template.InList:
        if isinstance(getattr(parent, "Proxy", None), analysis_mod.Analysis):
            parent.addObject(obj)
    return obj


def _renumber_copies(placed: List[Placement]) -> None:
    """Label each template's installed copies 1, 2, 3 ... (not the candidate numbers the
    optimum happened to use, "copy1, copy3, copy4"), keeping their order. Ascending, each new
    label is free: the object that held it was deleted or already renumbered lower."""
    by_template: Dict[str, List[Placement]] = {}
    for p in placed:
        if p.obj is not None and p.obj is not p.template:
            by_template.setdefault(p.template.Name, []).append(p)
    for copies in by_template.values():
        for number, p in enumerate(copies, start=1):
            label = f"{p.template.Label}{COPY_SUFFIX}{number}"
            if p.obj.Label != label:
                p.obj.Label = label


def _move_to(obj: Any, position_m: List[float]) -> None:
    """Put the luminaire's global position at ``position_m`` (parents' placements kept)."""
    target = FreeCAD.Vector(*position_m) * (1.0 / MM_TO_M)
    shift = target - obj.getGlobalPlacement().Base
    placement = obj.Placement
    placement.Base = placement.Base + shift
    obj.Placement = placement


def default_intention(target: Any) -> Tuple[str, Optional[float], Optional[float]]:
    """(goal, min_mean_lux, min_uniformity) a designer means for ``target``: with a required Em
    on a grid, "meet Em and U0 with the least installed flux"; otherwise the most light."""
    lux = float(getattr(target, "RequiredLux", 0.0) or 0.0)
    u0 = float(getattr(target, "RequiredUniformity", 0.0) or 0.0)
    if getattr(target, "TargetType", "") == "Grid" and lux > 0.0:
        return "minimize_installed_flux", lux, u0
    return "maximize_mean_illuminance", None, None


def _copies(template: Any, luminaires: List[Any]) -> Dict[int, Any]:
    """The template's copies among ``luminaires``, by copy number (from their labels)."""
    pattern = re.compile(_COPY_RE.format(re.escape(template.Label), COPY_SUFFIX))
    out = {}
    for obj in luminaires:
        match = pattern.match(obj.Label)
        if match and obj is not template:
            out[int(match.group(1))] = obj
    return out


def others_on_domains(analysis: Any) -> List[Any]:
    """Luminaires of the analysis that sit on a placement domain's face but are neither a
    domain's template nor one of its copies: what a designer expects the optimized layout to
    replace, and what must not be touched without asking."""
    import Part

    domains = [d for d in analysis_mod.placement_domains(analysis) if d.Template is not None]
    own = set()
    for d in domains:
        own.add(d.Template.Name)
        own.update(o.Name for o in _copies(d.Template, analysis_mod.luminaires(analysis)).values())
    out = []
    for lum in analysis_mod.luminaires(analysis):
        if lum.Name in own:
            continue
        point = Part.Vertex(lum.getGlobalPlacement().Base)
        for d in domains:
            try:
                face = domain_mod.domain_face(d)
            except ValueError:
                continue
            if point.distToShape(face)[0] <= float(d.MountingOffset) + ON_FACE_TOLERANCE_MM:
                out.append(lum)
                break
    return out


def placements(analysis: Any, goal: str = "") -> Tuple[List[Placement], List[Any], Report]:
    """The luminaires to place: per domain with a template, the template and MaxLuminaires - 1
    copies (those beyond MinLuminaires optional when minimising installed flux), and the copies
    beyond MaxLuminaires left by an earlier run (to remove). Domains without a template are
    reported and skipped."""
    report = Report()
    out: List[Placement] = []
    stale: List[Any] = []
    owner: Dict[str, Any] = {}  # template name -> the domain that places it
    for domain in analysis_mod.placement_domains(analysis):
        template = domain.Template
        if template is None:
            report.add("warning", f"Placement domain '{domain.Label}' has no Template luminaire: "
                                  "skipped", domain.Name)
            continue
        if template.Name in owner:
            report.add("error", f"Placement domains '{owner[template.Name].Label}' and "
                                f"'{domain.Label}' both place '{template.Label}': give each its "
                                "own Template", domain.Name)
            continue
        owner[template.Name] = domain
        count, least = int(domain.MaxLuminaires), max(1, int(domain.MinLuminaires))
        variable = goal == "minimize_installed_flux"
        if least != count and not variable:
            report.add("warning", f"Placement domain '{domain.Label}': this goal places exactly "
                                  f"MaxLuminaires = {count}; only 'minimize_installed_flux' "
                                  "chooses the count", domain.Name)
        copies = _copies(template, analysis_mod.luminaires(analysis))
        out.append(Placement(template.Name, template, domain, template, template.Label))
        for k in range(1, count):
            existing = copies.pop(k, None)
            name = existing.Name if existing is not None else f"{template.Name}{COPY_SUFFIX}{k}"
            out.append(Placement(name, template, domain, existing,
                                 f"{template.Label}{COPY_SUFFIX}{k}", variable and k >= least))
        stale.extend(copies.values())
    if not out:
        report.add("error", "No placement domain with a Template luminaire to optimize")
    return out, stale, report


def optimization_block(placed: List[Placement], goal: str, target: Any,
                       min_mean_lux: Optional[float], min_uniformity: Optional[float],
                       iterations: int, seed: int, evaluations: Optional[int] = None,
                       flux_lm: Optional[Dict[str, float]] = None,
                       fixed_m: Sequence[Sequence[float]] = ()) -> Dict[str, Any]:
    """The scene's ``optimization`` block (docs/optimization.md §10): one position variable per
    placed luminaire; per optional one a flux variable with levels (0, the template's flux), so
    that minimising the installed flux chooses how many to install; the search starts from an
    even layout of all of them (luminaires never share a cell: the optimizer refuses such
    configurations, and ``min_spacing_m`` is the largest :func:`spacing_of` the domains).
    ``fixed_m``: where the luminaires that stay are (the start keeps away from them)."""
    if goal not in GOALS:
        raise ValueError(f"goal must be one of {', '.join(GOALS)} (got {goal!r})")
    intention: Dict[str, Any] = {"type": goal, "target": target.Name}
    if goal in ("maximize_uniformity", "minimize_installed_flux"):
        if min_mean_lux is None:
            raise ValueError(f"goal {goal!r} needs min_mean_lux")
        intention["min_mean_lux"] = float(min_mean_lux)
    if goal == "minimize_installed_flux":
        if min_uniformity is None:
            raise ValueError("goal 'minimize_installed_flux' needs min_uniformity")
        intention["min_uniformity"] = float(min_uniformity)
    domains = {p.domain.Name: p.domain for p in placed}
    rectangles = {name: domain_mod.optimization_rectangle(d) for name, d in domains.items()}
    variables = [dict(rectangles[p.domain.Name], type="position", luminaire=p.name)
                 for p in placed]
    spacing_mm = {name: spacing_of(d) for name, d in domains.items()}
    start: List[int] = []
    for name, d in domains.items():
        mine = [p for p in placed if p.domain.Name == name]
        avoid = [[c / MM_TO_M for c in xyz] for xyz in fixed_m]
        for i, j in domain_mod.spread_cells(d, len(mine), spacing_mm[name], avoid):
            start += [i, j]
    flux_lm = flux_lm or {}
    for p in placed:
        if p.optional and p.template.Name in flux_lm:
            variables.append({"type": "flux", "luminaire": p.name,
                              "levels_lm": [0.0, float(flux_lm[p.template.Name])]})
            start.append(1)  # installed
    # A micrometre of slack: lattice points a spacing apart must not fail on rounding.
    spacing_m = max(0.0, max(spacing_mm.values()) * MM_TO_M - 1e-6)
    search: Dict[str, Any] = {"seed": int(seed), "max_iterations": int(iterations),
                              "min_spacing_m": spacing_m, "initial": [start]}
    if evaluations:
        search["max_evaluations"] = int(evaluations)
    return {"intention": intention, "variables": variables, "search": search}


def _anchor_m(lum: Dict[str, Any]) -> List[float]:
    """Where a scene luminaire is (m): its position, or the centre of its parallelogram (the
    optimizer's anchor)."""
    if "position" in lum:
        return list(lum["position"])
    return [c + 0.5 * (a + b) for c, a, b in zip(lum["corner"], lum["edge1"], lum["edge2"])]


def spacing_of(domain: Any) -> float:
    """Smallest distance (mm) between the domain's luminaires and any other: its MinSpacing,
    and at least the template's size for an area luminaire, so that panels never overlap."""
    spacing = float(domain.MinSpacing)
    template = domain.Template
    if template is not None and getattr(template, "LuminaireType", "") == "Area":
        spacing = max(spacing, float(template.Width), float(template.Length))
    return spacing


def with_copies(scene: Dict[str, Any], placed: List[Placement],
                left_out: List[Any]) -> Dict[str, Any]:
    """The scene with the templates' copies added to its luminaires (same entry, new name) and
    the luminaires in ``left_out`` (those the layout replaces) removed. Every placed luminaire
    is its own group in the search: the solver then re-traces only the one a step moves, and a
    flux level (an optional copy left out or installed) scales its trace instead of tracing
    (docs/optimization.md, "Reused traces"). Light scenes do not enter the search."""
    scene = copy.deepcopy(scene)
    gone = {o.Name for o in left_out}
    scene["luminaires"] = [lum for lum in scene["luminaires"] if lum["name"] not in gone]
    by_name = {lum["name"]: lum for lum in scene["luminaires"]}
    for p in placed:
        if p.name in by_name:
            continue
        if p.template.Name not in by_name:
            raise CheckError(Report.one(
                "error", f"Template '{p.template.Label}' of placement domain "
                         f"'{p.domain.Label}' is not a luminaire of the analysis"))
        entry = dict(by_name[p.template.Name], name=p.name)
        scene["luminaires"].append(entry)
        by_name[p.name] = entry
    for p in placed:
        by_name[p.name]["group"] = p.name
    return scene


@dataclass
class PreparedSearch:
    """What the search needs, made on the GUI thread (the export reads the document)."""

    placements: List[Placement]
    scene_file: str
    doc: Any
    report: Report
    removed: List[Any] = field(default_factory=list)
    max_iterations: int = 0
    max_evaluations: int = 0


def prepare(analysis: Any, target: Any, goal: str, min_mean_lux: Optional[float],
            min_uniformity: Optional[float], iterations: int, seed: int,
            output_dir: str, evaluations: Optional[int] = None,
            replace_others: bool = False) -> PreparedSearch:
    """Check the domains, export the scene with the copies and the ``optimization`` block to
    ``<output_dir>/optimization/scene.json``. ``replace_others``: the luminaires on a domain's
    face that no domain places (:func:`others_on_domains`) are left out of the search and
    deleted by apply(); otherwise they stay, and their light counts."""
    from lighting.export import scene as scene_mod

    placed, removed, report = placements(analysis, goal)
    if not report.ok:
        raise CheckError(report)
    if replace_others:
        removed = removed + others_on_domains(analysis)
    exported = scene_mod.build_scene(analysis)
    if not exported.report.ok:
        raise CheckError(exported.report)
    report.merge(exported.report)
    flux = {lum["name"]: lum["flux_lm"] for lum in exported.scene["luminaires"]
            if isinstance(lum.get("flux_lm"), (int, float))}
    exported.scene = with_copies(exported.scene, placed, removed)
    moved = {p.name for p in placed}
    fixed = [_anchor_m(lum) for lum in exported.scene["luminaires"]
             if lum["name"] not in moved and lum.get("type") != "directional"]
    block = optimization_block(placed, goal, target, min_mean_lux, min_uniformity, iterations,
                               seed, evaluations, flux, fixed)
    # In the file, so `lightsolver optimize <file>` repeats the search from a shell.
    exported.scene["optimization"] = block
    folder = os.path.join(output_dir, "optimization")
    scene_file = scene_mod.write_scene(exported, folder, analysis.MeshStorage)
    return PreparedSearch(placed, scene_file, analysis.Document, report, removed,
                          int(iterations), int(evaluations or 0))


def eta_seconds(stats: Dict[str, Any], max_iterations: int,
                max_evaluations: int = 0) -> Optional[float]:
    """Seconds left, from the measured time per evaluation (trace) times the evaluations left:
    those of the evaluation budget, or (once an iteration has finished) the iterations left at
    the evaluations per iteration seen so far, whichever ends first. None before anything is
    measured or when no budget bounds the run."""
    done, elapsed = int(stats.get("evaluations", 0)), float(stats.get("elapsed_seconds", 0.0))
    if done < 2 or elapsed <= 0.0:  # one trace says little (the first has start-up costs)
        return None
    left: List[float] = []
    if max_evaluations > 0:
        left.append(max(0, max_evaluations - done))
    iterations = int(stats.get("iteration", 0))
    if iterations > 0 and max_iterations > 0:
        left.append(max(0, max_iterations - iterations) * done / iterations)
    return min(left) * elapsed / done if left else None


def format_progress(stats: Dict[str, Any], max_iterations: int, max_evaluations: int = 0) -> str:
    """One line for the panel and the report view: work done, best so far, time left."""
    budget = f" of {max_evaluations}" if max_evaluations else ""
    text = (f"{stats.get('evaluations', 0)}{budget} evaluations, iteration "
            f"{stats.get('iteration', 0)} of {max_iterations}")
    best = stats.get("best")
    if best:
        text += f"; best {best[0]:.4g} ({stats.get('isoc_size', 0)} optima)"
    else:
        text += "; no feasible layout yet"
    eta = eta_seconds(stats, max_iterations, max_evaluations)
    text += f"; about {_duration(eta)} left" if eta is not None else "; estimating time"
    return text


def _duration(seconds: float) -> str:
    seconds = int(round(seconds))
    return f"{seconds // 60} min {seconds % 60:02d} s" if seconds >= 60 else f"{seconds} s"


def search(prepared: PreparedSearch,
           progress: Optional[Callable[[Dict[str, Any]], Any]] = None,
           screening_photons: Optional[int] = None,
           confirmation_photons: Optional[int] = None,
           cancel: Optional[Any] = None) -> PlacementResult:
    """Run the optimizer on the prepared scene file; safe on a worker thread (the module
    releases the GIL and touches no FreeCAD object). ``progress`` gets a dict after traces
    (``event`` "evaluation", at most 4 per second) and iterations, with ``eta_s`` added; it
    may return False to stop. ``cancel`` (a ``lightsolver.CancelToken``) stops it within one
    trace."""
    from lighting.solver import run

    def report(stats: Dict[str, Any]) -> Any:
        stats["eta_s"] = eta_seconds(stats, prepared.max_iterations, prepared.max_evaluations)
        return progress(stats)

    module = run.load_module()
    try:
        raw = module.optimize(prepared.scene_file, progress=report if progress else None,
                              cancel=cancel, screening_photons=screening_photons,
                              confirmation_photons=confirmation_photons)
    except (RuntimeError, ValueError) as exc:
        raise SolverError(f"The optimizer rejected the problem: {exc}") from exc
    return PlacementResult(raw, prepared.placements, prepared.scene_file, prepared.doc,
                           prepared.report, list(prepared.removed))


def run_optimization(analysis: Any, target: Any, goal: Optional[str],
                     min_mean_lux: Optional[float], min_uniformity: Optional[float],
                     iterations: int, seed: int, output_dir: str,
                     progress: Optional[Callable[[Dict[str, Any]], Any]] = None,
                     screening_photons: Optional[int] = None,
                     confirmation_photons: Optional[int] = None,
                     evaluations: Optional[int] = None,
                     replace_others: bool = False) -> PlacementResult:
    """Prepare, then search, on the calling thread. ``goal`` None: :func:`default_intention`
    (its required levels fill ``min_mean_lux`` / ``min_uniformity`` left None)."""
    if goal is None:
        goal, lux, u0 = default_intention(target)
        min_mean_lux = lux if min_mean_lux is None else min_mean_lux
        min_uniformity = u0 if min_uniformity is None else min_uniformity
    prepared = prepare(analysis, target, goal, min_mean_lux, min_uniformity, iterations, seed,
                       output_dir, evaluations, replace_others)
    return search(prepared, progress, screening_photons, confirmation_photons)
