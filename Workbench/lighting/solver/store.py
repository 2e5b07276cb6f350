# SPDX-License-Identifier: LGPL-2.1-or-later
"""Keep results in the document: one results object per analysis, in its group
(objects/results.py), holds the results JSON and the files of the run; saved in the .FCStd, so
a reopened file shows them without re-running. Targets, luminaires and the analysis' settings
stay inputs: nothing is written onto them except the analysis' Status. Writes are one undoable
transaction. Nothing here paints: in the GUI the view providers repaint when the results
object changes (their ``updateData``)."""
from __future__ import annotations

import json
from typing import Any, Dict, Optional, Tuple

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


def _required(analysis: Any) -> Dict[str, Tuple[float, float]]:
    return {t.Name: (float(t.RequiredLux), float(t.RequiredUniformity))
            for t in analysis_mod.targets(analysis)}


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
                      results_file: str = "") -> AnalysisResult:
    """Store results (``lightsolver.results/1`` layout, plain JSON data) in the analysis'
    results object, created on the first run and updated by the next (one undo step)."""
    doc = analysis.Document
    migrate(analysis)
    doc.openTransaction("Lighting results")
    try:
        obj = results_obj.of_analysis(analysis) or _make_results(analysis)
        _set(obj, "SceneFile", scene_file)
        _set(obj, "ResultsFile", results_file)
        _set(obj, "ResultsJson", json.dumps(data, separators=(",", ":")))
        _set(analysis, "SceneFile", scene_file)
        _set(analysis, "Status", "partial results (cancelled)" if data.get("partial") else "done")
    finally:
        doc.commitTransaction()
    return load_from_document(analysis)


def load_from_document(analysis: Any) -> Optional[AnalysisResult]:
    """The results of the analysis' results object, or None if it has none."""
    obj = results_object(analysis)
    data = results_obj.data(obj)
    if data is None:
        return None
    return AnalysisResult.from_data(data, _labels(analysis), _required(analysis), obj.SceneFile,
                                    obj.ResultsFile)


def clear(analysis: Any) -> None:
    """Remove the analysis' results object (one undo step)."""
    doc = analysis.Document
    migrate(analysis)
    doc.openTransaction("Clear lighting results")
    try:
        obj = results_obj.of_analysis(analysis)
        if obj is not None:
            analysis.removeObject(obj)
            doc.removeObject(obj.Name)
        _set(analysis, "Status", "not run")
    finally:
        doc.commitTransaction()


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
    """Update the analysis' Status without an undo step."""
    _set(analysis, "Status", text)


def set_scene_file(analysis: Any, path: str) -> None:
    """Record the last exported scene file without an undo step."""
    _set(analysis, "SceneFile", path)
