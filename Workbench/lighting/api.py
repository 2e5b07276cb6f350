# SPDX-License-Identifier: LGPL-2.1-or-later
"""Scripting API behind ``import lighting`` (headless and GUI).

Every function takes a document (or an analysis object); without ``analysis`` the
document's first Lighting analysis is used, and :func:`analyze` creates one with default
settings when the document has none."""
from __future__ import annotations

from typing import Any, Callable, Dict, List, Optional, Tuple

from lighting.messages import CheckError, Report
from lighting.objects import analysis as analysis_mod


def _analysis(doc_or_analysis: Any, analysis: Any = None, create: bool = False) -> Any:
    if analysis is not None and not isinstance(analysis, str):
        return analysis
    proxy = getattr(doc_or_analysis, "Proxy", None)
    if isinstance(proxy, analysis_mod.Analysis):
        return doc_or_analysis
    doc = doc_or_analysis
    found = analysis_mod.find_analysis(doc, analysis)
    if found is None:
        if analysis is not None:
            raise KeyError(f"No Lighting analysis named {analysis!r} in '{doc.Name}'")
        if not create:
            raise CheckError(Report.one("error",
                                        f"Document '{doc.Name}' has no Lighting analysis"))
        from lighting.objects.factory import make_analysis

        found = make_analysis(doc)
    return found


def _console_log(level: str, text: str) -> None:
    import FreeCAD

    line = f"Lighting: {text}\n"
    if level == "error":
        FreeCAD.Console.PrintError(line)
    elif level == "warning":
        FreeCAD.Console.PrintWarning(line)
    else:
        FreeCAD.Console.PrintLog(line)


def analyze(doc: Any, analysis: Any = None, photons: Optional[int] = None,
            seed: Optional[int] = None, accuracy: Optional[float] = None,
            output_dir: Optional[str] = None,
            progress: Optional[Callable[[int, int], Any]] = None) -> Any:
    """Check, export, solve and store the results of a lighting analysis.

    Args:
        doc: the FreeCAD document (or the analysis object itself).
        analysis: an analysis object or its name/label; default: the document's first one
            (created with defaults if there is none).
        photons, seed, accuracy: if given, written to the analysis' Photons, Seed and
            TargetAccuracy first (so the document and the scene file agree).
        output_dir: where scene.json and results.json go (default: the analysis'
            OutputDirectory, else '<document>_lighting/<analysis>' next to the file).
        progress: ``progress(done, total)``; return False to cancel (partial results).

    Returns:
        :class:`lighting.AnalysisResult` (``.table()``, ``["Workplane"].mean_lux``...).

    Raises:
        CheckError (model not ready), SolverUnavailableError, SolverError, CancelledError.
    """
    from lighting.solver.machine import run_analysis

    obj = _analysis(doc, analysis, create=True)
    if photons is not None:
        obj.Photons = int(photons)
    if seed is not None:
        obj.Seed = int(seed)
    if accuracy is not None:
        obj.TargetAccuracy = float(accuracy)
    result = run_analysis(obj, output_dir, progress, _console_log)
    obj.Document.recompute()
    return result


def optimize_placement(doc: Any, target: Any, goal: Optional[str] = None,
                       min_mean_lux: Optional[float] = None,
                       min_uniformity: Optional[float] = None, iterations: int = 200,
                       seed: int = 1, analysis: Any = None, output_dir: Optional[str] = None,
                       screening_photons: Optional[int] = None,
                       confirmation_photons: Optional[int] = None,
                       progress: Optional[Callable[[dict], Any]] = None,
                       evaluations: Optional[int] = None,
                       replace_others: bool = False) -> Any:
    """Find where the placement domains' luminaires should go (docs/optimization.md §12).

    Each placement domain with a Template places up to MaxLuminaires luminaires on its
    candidate lattice: the template and copies of it, never two in one place (nor closer than
    the domain's MinSpacing). The search returns every configuration statistically
    indistinguishable from the best.

    Args:
        target: the target object the intention is about.
        goal: None (default): what the target asks for - with a required Em on a grid,
            "minimize_installed_flux" ("meet Em and U0 with the least installed flux": the
            search also chooses how many luminaires, between MinLuminaires and MaxLuminaires),
            else "maximize_mean_illuminance". Or one of "minimize_installed_flux" (needs
            min_mean_lux and min_uniformity), "maximize_uniformity" (needs min_mean_lux),
            "maximize_mean_illuminance", "minimize_mean_illuminance". Required levels left
            None come from the target's RequiredLux / RequiredUniformity with goal None.
        iterations, evaluations, seed: the search's budgets (evaluations = traces; None: no
            limit) and seed; screening_photons (n), confirmation_photons (N): the adaptive
            photon counts (default: the optimizer's).
        progress: called within seconds of the start and then at most 4 times a second with a
            dict (evaluations, iteration, elapsed_seconds, best, isoc_size, eta_s = estimated
            seconds left or None); return False to stop.
        replace_others: the luminaires on a domain's face that no domain places (e.g. a
            layout drawn by hand) are left out of the search and deleted by apply(). False
            (default): they are kept, untouched, and their light counts.

    Returns:
        :class:`lighting.solver.optimize.PlacementResult`: ``.members`` (distinct layouts,
        best first, with ``positions_m`` per installed luminaire) and ``.apply(member=0)``,
        which leaves exactly that layout's luminaires for the domains (one undo step).
    """
    from lighting.export.scene import default_output_directory
    from lighting.solver.optimize import run_optimization

    obj = _analysis(doc, analysis)
    return run_optimization(obj, target, goal, min_mean_lux, min_uniformity, iterations, seed,
                            output_dir or default_output_directory(obj), progress,
                            screening_photons, confirmation_photons, evaluations,
                            replace_others)


def check(doc: Any, analysis: Any = None, need_solver: bool = True) -> Report:
    """The Check stage's report (never raises for model problems)."""
    from lighting.solver.check import check_analysis

    return check_analysis(_analysis(doc, analysis), need_solver=need_solver)


def export_scene(doc: Any, analysis: Any = None, directory: Optional[str] = None,
                 storage: Optional[str] = None) -> str:
    """Write the analysis' scene file (docs/scene-format.md) and return its path, without
    solving. ``storage``: "Inline", "PLY" or "Auto" (default: the analysis' MeshStorage).
    Raises CheckError when the model cannot make a valid scene."""
    from lighting.export.scene import build_scene, default_output_directory, write_scene

    obj = _analysis(doc, analysis)
    result = build_scene(obj)
    if not result.report.ok:
        raise CheckError(result.report)
    path = write_scene(result, directory or default_output_directory(obj),
                       storage or obj.MeshStorage)
    obj.SceneFile = path
    return path


def results(doc: Any, analysis: Any = None) -> Optional[Any]:
    """The results stored in the document (no solving), or None."""
    from lighting.solver.store import load_from_document

    return load_from_document(_analysis(doc, analysis))


def report(doc: Any, path: str, analysis: Any = None, date: Optional[str] = None,
           title: Optional[str] = None, *, allow_stale: bool = False,
           allow_partial: bool = False, allow_unverified: bool = False,
           signoff: Optional[Dict[str, Any]] = None, view_png: Optional[str] = None) -> str:
    """Write the calculation report of the stored results (docs/report.md) to ``path``:
    ``.html`` or ``.pdf``, written whole or not at all, into a folder that exists. Cover with
    the verdicts, luminaire schedule, surfaces, per target Em/Emin/Emax/U0/Ud with their
    intervals, requirements and verdicts, false-colour plans and value charts of the grids,
    the run's warnings; the results as traced, whatever light scene is shown, and a table per
    light scene of the analysis. The analysis' Report properties (ProjectName, ProjectNumber,
    Client, PreparedBy, CheckedBy, ReportDate, the LENI inputs) fill in project, names, date
    and energy. ``date`` (YYYY-MM-DD; default by ReportDate: today) and ``title`` (default:
    ProjectName, else the document's label) are printed on it; ``signoff`` ({project, author,
    checked_by}) overrides the analysis' names and what the document says (its label,
    CreatedBy, Company); ``view_png`` is a picture of the model for the report (the Report
    command passes the 3D view). Returns the path written.

    Refused: results that no longer describe the model unless ``allow_stale`` (then marked
    stale), a cancelled run's unless ``allow_partial`` (then marked partial on every page),
    and what the generator refuses (results of another scene unless they cannot tell and
    ``allow_unverified``; broken or empty results; a missing folder).
    Raises CheckError (no results), StaleResultsError, PartialResultsError,
    SolverUnavailableError (no report generator) or LightingError (the report could not be
    written)."""
    from lighting.reporting import make_report

    return make_report(_analysis(doc, analysis), path, date=date, title=title,
                       allow_stale=allow_stale, allow_partial=allow_partial,
                       allow_unverified=allow_unverified, signoff=signoff, view_png=view_png)


def exclude(objects: Any, excluded: bool = True) -> List[Any]:
    """Leave objects out of the lighting model (``excluded=False``: take them back in), in one
    undo step; returns the objects whose state changed. Sets each object's ``LightingExclude``
    property (added when missing); excluding a group, App::Part or building part leaves out
    everything in it. Hidden objects are *not* left out: only exclusion does that."""
    from lighting.export.collect import set_excluded
    from lighting.solver.store import undo_step

    items = list(objects) if isinstance(objects, (list, tuple, set)) else [objects]
    if not items:
        return []
    changed: List[Any] = []
    title = "Exclude from lighting" if excluded else "Include in lighting"
    with undo_step(items[0].Document, title):
        for obj in items:
            if set_excluded(obj, excluded):
                changed.append(obj)
    return changed


def left_out(doc: Any) -> List[Tuple[Any, str]]:
    """(object, reason) for each object that could be geometry but is not exported: excluded
    (itself or with its container), without faces, an Arch space... (Check lists them)."""
    from lighting.export.collect import left_out as collect_left_out

    return [(obj, reason) for obj, _, reason in collect_left_out(doc)]


def results_state(doc: Any, analysis: Any = None) -> Any:
    """Whether the stored results still describe the model: a ``ResultsState`` with
    ``.state`` ("none", "current", "stale", "unknown"), ``.stale``, ``.changes`` (what changed
    since the run) and ``.text()``. Computed from the model now, without exporting."""
    from lighting.solver.store import results_state as state_of

    return state_of(_analysis(doc, analysis))


def solver_available() -> Tuple[bool, str]:
    """(True, module path) if the native solver can be imported, else (False, reason)."""
    from lighting.solver.run import solver_available as available

    return available()


def luminaire_library_entries(folder: Optional[str] = None, shipped: bool = True) -> list:
    """The luminaire library: the shipped photometric files and the user folder's (``folder``;
    default: the LuminaireFolder preference), each a
    :class:`lighting.luminaire_library.LibraryEntry` with the native parser's facts
    (``.lamp_lumens_lm``, ``.facts()``) or its ``.error`` for a file the parser rejects."""
    from lighting import luminaire_library

    return luminaire_library.list_entries(folder, shipped)


def assign_photometry(doc: Any, luminaires: Any, path: str, keep_flux: bool = False) -> list:
    """Make ``luminaires`` photometric with the file ``path`` in one undo step (FluxLumen from
    the file's lamp lumens unless ``keep_flux``); ValueError for a file the parser rejects."""
    from lighting import luminaire_library

    return luminaire_library.assign(doc, luminaires, path, keep_flux)


def add_luminaire_layout(doc: Any, base: Any = None, face: Optional[str] = None,
                         rows: int = 2, columns: int = 2, spacing_x_m: float = 0.0,
                         spacing_y_m: float = 0.0, margin_x_m: float = 0.0,
                         margin_y_m: float = 0.0, offset_m: float = 0.05,
                         rotation_deg: float = 0.0, template: Any = None, kind: str = "Area",
                         flux_lm: float = 3000.0, maintenance_factor: float = 0.8,
                         width_m: float = 0.6, length_m: float = 0.6,
                         photometric_file: Optional[str] = None,
                         area_m: Optional[Tuple[float, float]] = None,
                         clip_to_walls: bool = True, name: str = "LuminaireLayout",
                         analysis: Any = None) -> Any:
    """A luminaire layout (field arrangement): ``rows`` x ``columns`` luminaires over the
    planar face ``base.face`` (a ceiling's underside) or, without ``base``, over a rectangle
    ``area_m`` = (length, width) in the layout's Placement plane.

    Spacing 0 fills the field between the margins; margin 0 is half the spacing (an even
    field); ``offset_m`` is the distance from the face (below a ceiling). The members share
    ``template`` (a luminaire), or a new hidden template made from ``kind``, ``flux_lm``,
    ``maintenance_factor``, ``width_m`` x ``length_m`` and ``photometric_file`` (it shows
    under the layout in the tree). The layout goes into ``analysis``' group when given (else
    into no analysis: every analysis uses it). Returns the layout; edit its Rows, Columns, ...
    later (the members follow)."""
    from lighting.objects.factory import make_luminaire
    from lighting.objects.luminaire_layout import make_layout
    from lighting.units import M_TO_MM

    if analysis is not None:
        analysis = _analysis(doc, analysis)
    if template is None:
        template = make_luminaire(doc, (0.0, 0.0, 0.0), kind=kind, flux_lm=flux_lm,
                                  maintenance_factor=maintenance_factor, width_m=width_m,
                                  length_m=length_m, name=f"{name}Type")
        if photometric_file:
            template.PhotometricFile = photometric_file
        template.Visibility = False
    lengths = {"SpacingX": spacing_x_m, "SpacingY": spacing_y_m, "MarginX": margin_x_m,
               "MarginY": margin_y_m, "MountingOffset": offset_m}
    lengths = {k: v * M_TO_MM for k, v in lengths.items()}
    if area_m is not None:
        lengths["AreaLength"], lengths["AreaWidth"] = (area_m[0] * M_TO_MM, area_m[1] * M_TO_MM)
    layout = make_layout(doc, template, base, face, rows, columns, name,
                         LuminaireRotation=rotation_deg, **lengths)
    layout.ClipToWalls = bool(clip_to_walls)
    if analysis is not None:
        analysis.addObject(layout)
    layout.recompute()
    return layout


def accuracy_study(doc: Any, analysis: Any = None, max_photons: int = 1_280_000,
                   output_dir: Optional[str] = None) -> Any:
    """What accuracy costs for the analysis' scene: ``lightsolver study`` (one run with
    doubling checkpoints). Returns a :class:`lighting.solver.study.StudyResult`: ``data``
    (rows: photons, seconds, mean and worst per-cell width; the N^-1/2 fit), ``goals``
    (photons and seconds for 10, 5, 2, 1 and 0.5 % per cell), ``plot_file`` (PNG)."""
    from lighting.solver.study import study_analysis

    return study_analysis(_analysis(doc, analysis), max_photons, output_dir)
