# SPDX-License-Identifier: LGPL-2.1-or-later
"""Keep results in the document: the analysis holds the results JSON and run facts, each
target its Em, Emin, Emax, U0, CIs and grid cells — saved in the .FCStd, so a reopened file
shows them without re-running. Writes are one undoable transaction. Nothing here paints: in
the GUI the view providers repaint when these properties change (their ``updateData``)."""
from __future__ import annotations

import json
from typing import Any, Dict, Optional, Tuple

from lighting.objects import analysis as analysis_mod
from lighting.objects.target import RESULT_FLOATS, RESULT_LISTS
from lighting.solver.results import AnalysisResult, TargetResult


def _required(analysis: Any) -> Dict[str, Tuple[float, float]]:
    return {t.Name: (float(t.RequiredLux), float(t.RequiredUniformity))
            for t in analysis_mod.targets(analysis)}


def _labels(analysis: Any) -> Dict[str, str]:
    doc = analysis.Document
    labels = {}
    for obj in doc.Objects:
        labels[obj.Name] = obj.Label
    return labels


def _set(obj: Any, name: str, value: Any) -> None:
    if getattr(obj, name) != value:
        setattr(obj, name, value)


def _write_target(obj: Any, result: Optional[TargetResult], analysis_name: str) -> None:
    if result is None:
        for name in RESULT_FLOATS:
            _set(obj, name, 0.0)
        for name in RESULT_LISTS:
            _set(obj, name, [])
        _set(obj, "HasResults", False)
        _set(obj, "ResultAnalysis", "")
        return
    values = {
        "MeanLux": result.mean_lux, "CiLowLux": result.ci_low_lux,
        "CiHighLux": result.ci_high_lux, "SigmaLux": result.sigma_lux, "Hits": result.hits,
        "AreaM2": result.area_m2, "MinLux": result.min_lux or 0.0,
        "MaxLux": result.max_lux or 0.0, "Uniformity": result.uniformity or 0.0,
        "MinCiLowLux": result.min_ci_lux[0], "MinCiHighLux": result.min_ci_lux[1],
        "MaxCiLowLux": result.max_ci_lux[0], "MaxCiHighLux": result.max_ci_lux[1],
    }
    for name, value in values.items():
        _set(obj, name, float(value))
    _set(obj, "CellsLux", list(result.cells_lux))
    _set(obj, "CellsCiLowLux", list(result.cells_ci_low_lux))
    _set(obj, "CellsCiHighLux", list(result.cells_ci_high_lux))
    _set(obj, "CellsHits", list(result.cells_hits))
    _set(obj, "HasResults", True)
    _set(obj, "ResultAnalysis", analysis_name)


def apply_to_document(analysis: Any, data: Dict[str, Any], scene_file: str = "",
                      results_file: str = "") -> AnalysisResult:
    """Store normalised results in the analysis and its targets (one undo step)."""
    doc = analysis.Document
    result = AnalysisResult.from_data(data, _labels(analysis), _required(analysis),
                                      scene_file, results_file)
    doc.openTransaction("Lighting results")
    try:
        by_name = {t.name: t for t in result.targets}
        for tgt in analysis_mod.targets(analysis):
            _write_target(tgt, by_name.get(tgt.Name), analysis.Name)
        _set(analysis, "ResultsJson", json.dumps(data, separators=(",", ":")))
        _set(analysis, "SceneFile", scene_file)
        _set(analysis, "ResultsFile", results_file)
        _set(analysis, "PhotonsTraced", float(result.photons))
        _set(analysis, "SolveSeconds", float(result.seconds))
        _set(analysis, "Partial", bool(result.partial))
        _set(analysis, "SolverWarnings", list(result.warnings))
        _set(analysis, "Status", "partial results (cancelled)" if result.partial else "done")
    finally:
        doc.commitTransaction()
    return result


def load_from_document(analysis: Any) -> Optional[AnalysisResult]:
    """The results stored in the analysis, or None if it has none."""
    if not analysis.ResultsJson:
        return None
    try:
        data = json.loads(analysis.ResultsJson)
    except ValueError:
        return None
    return AnalysisResult.from_data(data, _labels(analysis), _required(analysis),
                                    analysis.SceneFile, analysis.ResultsFile)


def clear(analysis: Any) -> None:
    """Remove stored results from the analysis and its targets (one undo step)."""
    doc = analysis.Document
    doc.openTransaction("Clear lighting results")
    try:
        for tgt in analysis_mod.targets(analysis):
            if tgt.ResultAnalysis in ("", analysis.Name):
                _write_target(tgt, None, analysis.Name)
        _set(analysis, "ResultsJson", "")
        _set(analysis, "PhotonsTraced", 0.0)
        _set(analysis, "SolveSeconds", 0.0)
        _set(analysis, "Partial", False)
        _set(analysis, "SolverWarnings", [])
        _set(analysis, "Status", "not run")
    finally:
        doc.commitTransaction()


def set_status(analysis: Any, text: str) -> None:
    """Update the analysis' Status without an undo step."""
    _set(analysis, "Status", text)


def set_scene_file(analysis: Any, path: str) -> None:
    """Record the last exported scene file without an undo step."""
    _set(analysis, "SceneFile", path)

