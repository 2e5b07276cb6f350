# SPDX-License-Identifier: LGPL-2.1-or-later
"""Keep results in the document: one results object per analysis, in its group
(objects/results.py), holds the results JSON and the files of the run; saved in the .FCStd, so
a reopened file shows them without re-running. Targets, luminaires and the analysis' settings
stay inputs: nothing is written onto them except the analysis' Status. Writes are one undoable
transaction. Nothing here paints: in the GUI the view providers repaint when the results
object changes (their ``updateData``)."""
from __future__ import annotations

import json
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, Dict, Iterator, List, Optional, Tuple

import FreeCAD

from lighting.export import fingerprint as fingerprint_mod
from lighting.objects import analysis as analysis_mod
from lighting.objects import results as results_obj
from lighting.solver.results import AnalysisResult

#: Properties that older versions wrote onto the analysis and onto its targets (migrate()).
LEGACY_ANALYSIS = ("ResultsJson", "ResultsFile", "PhotonsTraced", "SolveSeconds", "Partial",
                   "SolverWarnings")
LEGACY_TARGET = ("MeanLux", "CiLowLux", "CiHighLux", "SigmaLux", "MinLux", "MaxLux",
                 "Uniformity", "Hits", "AreaM2", "MinCiLowLux", "MinCiHighLux", "MaxCiLowLux",
                 "MaxCiHighLux", "CellsLux", "CellsCiLowLux", "CellsCiHighLux", "CellsHits",
                 "HasResults", "ResultAnalysis")


#: Results fields that differ between two runs of the same scene and seed.
RUN_FACTS = ("seconds",)


@contextmanager
def undo_step(doc: Any, title: str) -> Iterator[None]:
    """One undo transaction around a user action, or none when nothing changed.

    ``openTransaction`` only books a name: FreeCAD creates the transaction at the first
    change, and a commit without changes leaves the booking pending, so the next unrelated
    change (even seconds later) would be recorded under ``title``. Close it here."""
    doc.openTransaction(title)
    try:
        yield
    except BaseException:
        doc.abortTransaction()
        _close_booking(title)
        raise
    doc.commitTransaction()
    _close_booking(title)


def _close_booking(title: str) -> None:
    active = FreeCAD.getActiveTransaction() if hasattr(FreeCAD, "getActiveTransaction") else None
    if active and active[0] == title:
        FreeCAD.closeActiveTransaction()


def write_settings(analysis: Any, **values: Any) -> bool:
    """Set analysis properties (Photons=..., TargetAccuracy=...) in one undo step "Lighting
    settings", only if one of them differs; True when something changed."""
    changed = {k: v for k, v in values.items() if _differs(getattr(analysis, k), v)}
    if not changed:
        return False
    with undo_step(analysis.Document, "Lighting settings"):
        for name, value in changed.items():
            setattr(analysis, name, value)
    return True


def _differs(current: Any, value: Any) -> bool:
    if isinstance(value, float) or isinstance(current, float):
        return abs(float(current) - float(value)) > 1e-12
    return current != value


@dataclass
class ResultsState:
    """Whether an analysis' stored results describe the model as it is now.

    ``state``: "none" (no results), "current", "stale" (``changes`` says what changed since
    the run) or "unknown" (results of an older version, without a fingerprint)."""

    state: str
    changes: List[str] = field(default_factory=list)

    @property
    def stale(self) -> bool:
        """True when the model changed since the run."""
        return self.state == "stale"

    def text(self, limit: int = 3) -> str:
        """One line for people."""
        if self.state == "none":
            return "no results yet"
        if self.state == "current":
            return "results up to date"
        if self.state == "unknown":
            return "results of an older version: cannot tell whether they are current"
        shown = ", ".join(self.changes[:limit])
        more = f" and {len(self.changes) - limit} more" if len(self.changes) > limit else ""
        return f"results out of date (stale): {shown}{more} since the run"


def results_state(analysis: Any) -> ResultsState:
    """Compare the fingerprint stored by the last run with the model's now (no export)."""
    obj = results_obj.of_analysis(analysis)
    if obj is None or not obj.ResultsJson:
        return ResultsState("none")
    stored = fingerprint_mod.loads(getattr(obj, "InputsFingerprint", ""))
    if stored is None:
        return ResultsState("unknown")
    changes = fingerprint_mod.differences(stored, fingerprint_mod.of_analysis(analysis),
                                          analysis.Document)
    return ResultsState("stale", changes) if changes else ResultsState("current")


def settled_status(analysis: Any) -> str:
    """The Status that describes the analysis' stored results."""
    return results_obj.status_of(results_obj.data(results_obj.of_analysis(analysis)))


def _same_results(old: Optional[Dict[str, Any]], new: Dict[str, Any]) -> bool:
    """The two results agree but for when, where and how the runs were started."""
    if old is None:
        return False
    from lighting.solver.results import reader

    strip = reader().without_run_facts
    return strip(old, RUN_FACTS) == strip(json.loads(json.dumps(new)), RUN_FACTS)


def summary_line(result: AnalysisResult, limit: int = 3) -> str:
    """One short line for the status bar: "done: Workplane Em 575 lx U0 0.71 (500 lx: pass),
    Desk top 612 lx; 200000 photons, 1.2 s"."""
    parts = []
    for t in result.targets[:limit]:
        text = (f"{t.label} {t.ugr_text()[0]}" if t.is_glare
                else f"{t.label} Em {t.mean_lux:.0f} lx")
        if t.kind == "grid":
            text += f" U0 {t.uniformity:.2f}"
        verdict = t.verdict_text()
        if verdict:
            text += f" {verdict}"
        parts.append(text)
    if len(result.targets) > limit:
        parts.append(f"+{len(result.targets) - limit} more")
    state = "partial results" if result.partial else "done"
    # Tracing time as traced: a decided run of 16 384 photons takes milliseconds, not "0.0 s".
    seconds = (f"{result.seconds * 1000.0:.0f} ms" if result.seconds < 1.0
               else f"{result.seconds:.1f} s")
    return f"{state}: {', '.join(parts)}; {result.photons:.0f} photons traced in {seconds}"


def _labels(analysis: Any) -> Dict[str, str]:
    return {obj.Name: obj.Label for obj in analysis.Document.Objects}


def _set(obj: Any, name: str, value: Any) -> None:
    if getattr(obj, name) != value:
        setattr(obj, name, value)


def _make_results(analysis: Any) -> Any:
    from lighting.objects.results import Results

    obj = analysis.Document.addObject("App::FeaturePython", "LightingResults")
    Results(obj)
    obj.Label = f"{analysis.Label} results"
    analysis.addObject(obj)
    return obj


def results_object(analysis: Any) -> Optional[Any]:
    """The analysis' results object (migrating results stored the old way first), or None."""
    migrate(analysis)
    return results_obj.of_analysis(analysis)


def apply_to_document(analysis: Any, data: Dict[str, Any], scene_file: str = "",
                      results_file: str = "",
                      fingerprint: Optional[Dict[str, str]] = None) -> AnalysisResult:
    """Store results (``lightsolver.results/1`` layout, plain JSON data) in the analysis'
    results object, created on the first run and updated by the next (one undo step).
    ``fingerprint``: of the model the run exported (export/fingerprint.py; default: the
    model's now). A run that found exactly the stored results for the same model (a second
    Run without changes) changes nothing and adds no undo step."""
    doc = analysis.Document
    migrate(analysis)
    prints = fingerprint_mod.dumps(fingerprint if fingerprint is not None
                                   else fingerprint_mod.of_analysis(analysis))
    status = results_obj.status_of(data)
    existing = results_obj.of_analysis(analysis)
    if existing is not None and existing.InputsFingerprint == prints and \
            existing.SceneFile == scene_file and _same_results(results_obj.traced(existing), data):
        set_status(analysis, status)
        return load_from_document(analysis)
    with undo_step(doc, "Lighting results"):
        obj = existing or _make_results(analysis)
        _set(obj, "SceneFile", scene_file)
        _set(obj, "ResultsFile", results_file)
        _set(obj, "InputsFingerprint", prints)
        _set(obj, "ResultsJson", json.dumps(data, separators=(",", ":")))
        _set(analysis, "SceneFile", scene_file)
        _set(analysis, "Status", status)
    _settled(obj, analysis)
    return load_from_document(analysis)


def _settled(*objs: Any) -> None:
    """Nothing is left to recompute: the results object and the analysis compute nothing
    (their ``execute`` is empty), so storing results must not leave them touched. A touched
    object is saved as touched, and a reopened file then showed both as needing a recompute
    (GUI scenario toolbar_legend)."""
    for obj in objs:
        if obj is not None and hasattr(obj, "purgeTouched"):
            obj.purgeTouched()


@contextmanager
def _unrecorded(obj: Any, names: Tuple[str, ...]) -> Iterator[None]:
    """Writes to ``names`` of ``obj`` that neither land in an undo transaction nor mark the
    document modified (NoModify while they happen, as the analysis' bookkeeping properties)."""
    added = [n for n in names if n in obj.PropertiesList
             and "NoModify" not in obj.getPropertyStatus(n)]
    for name in added:
        obj.setPropertyStatus(name, "NoModify")
    try:
        yield
    finally:
        for name in added:
            obj.setPropertyStatus(name, "-NoModify")


def write_live(analysis: Any, data: Dict[str, Any], fingerprint: Dict[str, str],
               status: str) -> None:
    """Show a live frame (solver/live.py) through the results object, with no undo step: the
    frames of a live session are views of the model, not edits (the results object itself is
    created, unrecorded too, if the analysis has none)."""
    existing = results_obj.of_analysis(analysis)
    doc = analysis.Document
    if existing is None:
        if getattr(doc, "HasPendingTransaction", False):
            return  # the user is in the middle of an edit: the next frame creates it
        existing = _make_results(analysis)
    from lighting.objects.results import DERIVED

    names = ("ResultsJson", "InputsFingerprint", "SceneFile", "ResultsFile", *DERIVED)
    set_status(analysis, status)  # first: the legend repainted for the JSON reads it
    with _unrecorded(existing, names):
        _set(existing, "InputsFingerprint", fingerprint_mod.dumps(fingerprint))
        _set(existing, "ResultsJson", json.dumps(data, separators=(",", ":")))


def load_from_document(analysis: Any) -> Optional[AnalysisResult]:
    """The results of the analysis' results object, or None if it has none."""
    obj = results_object(analysis)
    data = results_obj.data(obj)
    if data is None:
        return None
    return AnalysisResult.from_data(data, _labels(analysis), analysis_mod.requirements(analysis),
                                    obj.SceneFile, obj.ResultsFile)


def clear(analysis: Any) -> None:
    """Remove the analysis' results object (one undo step)."""
    doc = analysis.Document
    migrate(analysis)
    with undo_step(doc, "Clear lighting results"):
        obj = results_obj.of_analysis(analysis)
        if obj is not None:
            analysis.removeObject(obj)
            doc.removeObject(obj.Name)
        _set(analysis, "Status", "not run")


def migrate(analysis: Any) -> bool:
    """Documents of older versions kept results on the analysis (ResultsJson, ...) and its
    targets (MeanLux, CellsLux, ...): move the JSON into a results object and remove those
    properties. Runs once, at the first use of the results (App) or when the GUI opened the
    document; True if anything changed."""
    legacy = [p for p in LEGACY_ANALYSIS if p in analysis.PropertiesList]
    if not legacy:
        return False
    text = analysis.ResultsJson if "ResultsJson" in legacy else ""
    files = analysis.ResultsFile if "ResultsFile" in legacy else ""
    if text and results_obj.of_analysis(analysis) is None:
        obj = _make_results(analysis)
        obj.SceneFile = analysis.SceneFile
        obj.ResultsFile = files
        obj.ResultsJson = text
    for name in legacy:
        analysis.removeProperty(name)
    for tgt in analysis_mod.targets(analysis):
        for name in LEGACY_TARGET:
            if name in tgt.PropertiesList:
                tgt.removeProperty(name)
    return True


def set_status(analysis: Any, text: str) -> None:
    """Update the analysis' Status without an undo step (the property is NoModify, so no
    pending transaction records it, objects/analysis.py)."""
    _set(analysis, "Status", text)


def set_scene_file(analysis: Any, path: str) -> None:
    """Record the last exported scene file without an undo step."""
    _set(analysis, "SceneFile", path)
