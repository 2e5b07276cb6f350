# SPDX-License-Identifier: LGPL-2.1-or-later
"""Inverse design from the document: where should the luminaires of the placement domains go?

Each placement domain with a ``Template`` luminaire places ``MaxLuminaires`` luminaires: the
template itself and copies of it, each a ``position`` variable (docs/optimization.md §10) on
the domain's candidate lattice (``placement_domain.optimization_rectangle``). The exported
scene gets the copies, the ``optimization`` block is built from the intention given here, and
``lightsolver.optimize`` returns the set of statistically indistinguishable optimal
configurations (ISOC). :meth:`PlacementResult.apply` moves the template and creates or moves
its copies in the document."""
from __future__ import annotations

import copy
import os
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Tuple

import FreeCAD

from lighting.messages import CheckError, Report, SolverError
from lighting.objects import analysis as analysis_mod
from lighting.objects import placement_domain as domain_mod
from lighting.units import MM_TO_M

GOALS = ("maximize_uniformity", "minimize_installed_flux", "maximize_mean_illuminance",
         "minimize_mean_illuminance")
COPY_SUFFIX = "_copy"


@dataclass
class Placement:
    """One luminaire the optimizer places: its scene name, template and domain, and its
    document object when it has one (the template, or a copy made by an earlier apply())."""

    name: str
    template: Any
    domain: Any
    obj: Optional[Any] = None
    label: str = ""


@dataclass
class PlacementResult:
    """The optimizer's answer: ISOC members, best first (format lightsolver.optimization/1)."""

    raw: Dict[str, Any]
    placements: List[Placement]
    scene_file: str
    doc: Any = None
    report: Report = field(default_factory=Report)

    @property
    def members(self) -> List[Dict[str, Any]]:
        """ISOC members: ``positions_m`` (luminaire name -> [x, y, z]), ``mean``, ``ci``."""
        out = []
        for m in self.raw["isoc"]:
            obj = m["objective"]
            out.append({"positions_m": {p.name: m["scene"][p.name] for p in self.placements},
                        "mean": obj["mean"], "ci": (obj["ci_low"], obj["ci_high"])})
        return out

    def apply(self, member: int = 0) -> List[Any]:
        """Move the templates and create (or move) their copies to ISOC member ``member``;
        returns the luminaire objects placed, in placement order."""
        chosen = self.members[member]["positions_m"]
        placed = []
        for p in self.placements:
            if p.obj is None:
                p.obj = _new_copy(p)
            _move_to(p.obj, chosen[p.name])
            placed.append(p.obj)
        self.doc.recompute()
        return placed


def _new_copy(p: Placement) -> Any:
    """A copy of the template, labelled so the next optimization finds and reuses it, in the
    template's analyses."""
    obj = p.template.Document.copyObject(p.template)
    obj.Label = p.label
    for parent in p.template.InList:
        if isinstance(getattr(parent, "Proxy", None), analysis_mod.Analysis):
            parent.addObject(obj)
    return obj


def _move_to(obj: Any, position_m: List[float]) -> None:
    """Put the luminaire's global position at ``position_m`` (parents' placements kept)."""
    target = FreeCAD.Vector(*position_m) * (1.0 / MM_TO_M)
    shift = target - obj.getGlobalPlacement().Base
    placement = obj.Placement
    placement.Base = placement.Base + shift
    obj.Placement = placement


def placements(analysis: Any) -> Tuple[List[Placement], Report]:
    """The luminaires to place: per domain with a template, the template and MaxLuminaires - 1
    copies. Domains without a template are reported and skipped."""
    report = Report()
    out: List[Placement] = []
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
        count = int(domain.MaxLuminaires)
        if int(domain.MinLuminaires) != count:
            report.add("warning", f"Placement domain '{domain.Label}': the optimizer places "
                                  f"exactly MaxLuminaires = {count} (a variable count is not "
                                  "supported yet)", domain.Name)
        luminaires = {o.Label: o for o in analysis_mod.luminaires(analysis)}
        out.append(Placement(template.Name, template, domain, template, template.Label))
        for k in range(1, count):
            label = f"{template.Label}{COPY_SUFFIX}{k}"
            existing = luminaires.get(label)
            name = existing.Name if existing is not None else f"{template.Name}{COPY_SUFFIX}{k}"
            out.append(Placement(name, template, domain, existing, label))
    if not out:
        report.add("error", "No placement domain with a Template luminaire to optimize")
    return out, report


def optimization_block(placed: List[Placement], goal: str, target: Any,
                       min_mean_lux: Optional[float], min_uniformity: Optional[float],
                       iterations: int, seed: int) -> Dict[str, Any]:
    """The scene's ``optimization`` block (docs/optimization.md §10)."""
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
    rectangles = {p.domain.Name: domain_mod.optimization_rectangle(p.domain) for p in placed}
    variables = [dict(rectangles[p.domain.Name], type="position", luminaire=p.name)
                 for p in placed]
    return {"intention": intention, "variables": variables,
            "search": {"seed": int(seed), "max_iterations": int(iterations)}}


def with_copies(scene: Dict[str, Any], placed: List[Placement]) -> Dict[str, Any]:
    """The scene with the templates' copies added to its luminaires (same entry, new name)."""
    scene = copy.deepcopy(scene)
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
    return scene


@dataclass
class PreparedSearch:
    """What the search needs, made on the GUI thread (the export reads the document)."""

    placements: List[Placement]
    scene_file: str
    doc: Any
    report: Report


def prepare(analysis: Any, target: Any, goal: str, min_mean_lux: Optional[float],
            min_uniformity: Optional[float], iterations: int, seed: int,
            output_dir: str) -> PreparedSearch:
    """Check the domains, export the scene with the copies and the ``optimization`` block to
    ``<output_dir>/optimization/scene.json``."""
    from lighting.export import scene as scene_mod

    placed, report = placements(analysis)
    if not report.ok:
        raise CheckError(report)
    block = optimization_block(placed, goal, target, min_mean_lux, min_uniformity, iterations,
                               seed)
    exported = scene_mod.build_scene(analysis)
    if not exported.report.ok:
        raise CheckError(exported.report)
    report.merge(exported.report)
    exported.scene = with_copies(exported.scene, placed)
    # In the file, so `lightsolver optimize <file>` repeats the search from a shell.
    exported.scene["optimization"] = block
    folder = os.path.join(output_dir, "optimization")
    scene_file = scene_mod.write_scene(exported, folder, analysis.MeshStorage)
    return PreparedSearch(placed, scene_file, analysis.Document, report)


def search(prepared: PreparedSearch,
           progress: Optional[Callable[[Dict[str, Any]], Any]] = None,
           screening_photons: Optional[int] = None,
           confirmation_photons: Optional[int] = None,
           cancel: Optional[Any] = None) -> PlacementResult:
    """Run the optimizer on the prepared scene file; safe on a worker thread (the module
    releases the GIL and touches no FreeCAD object). ``progress`` may return False to stop;
    ``cancel`` (a ``lightsolver.CancelToken``) stops it within one trace."""
    from lighting.solver import run

    module = run.load_module()
    try:
        raw = module.optimize(prepared.scene_file, progress=progress, cancel=cancel,
                              screening_photons=screening_photons,
                              confirmation_photons=confirmation_photons)
    except (RuntimeError, ValueError) as exc:
        raise SolverError(f"The optimizer rejected the problem: {exc}") from exc
    return PlacementResult(raw, prepared.placements, prepared.scene_file, prepared.doc,
                           prepared.report)


def run_optimization(analysis: Any, target: Any, goal: str, min_mean_lux: Optional[float],
                     min_uniformity: Optional[float], iterations: int, seed: int,
                     output_dir: str,
                     progress: Optional[Callable[[Dict[str, Any]], Any]] = None,
                     screening_photons: Optional[int] = None,
                     confirmation_photons: Optional[int] = None) -> PlacementResult:
    """Prepare, then search, on the calling thread."""
    prepared = prepare(analysis, target, goal, min_mean_lux, min_uniformity, iterations, seed,
                       output_dir)
    return search(prepared, progress, screening_photons, confirmation_photons)
