# SPDX-License-Identifier: LGPL-2.1-or-later
"""Whether results belong to the scene a report is made for (docs/report.md, "Refusals").

A report prints one scene's luminaires, materials and requirements beside the results' numbers;
results of another scene, or of the same scene before its content or one of its files changed,
would make a report that nobody should sign. The results' ``provenance`` (docs/scene-format.md)
records the scene's content hash and every file it read; :func:`check` compares them with the
scene file as it is now through the solver's own comparison (``lightsolver.verify_results``,
the same as ``lightsolver verify SCENE RESULTS``) and raises
:class:`lightsolver_report.ReportError` naming each difference."""
from __future__ import annotations

import os
from typing import Any, Dict, List, Union

__all__ = ["check", "differences", "verifiable"]

PathLike = Union[str, "os.PathLike[str]"]


def _report_error(message: str) -> Exception:
    # Imported here: the package's __init__ imports modules that may import this one.
    from lightsolver_report import ReportError

    return ReportError(message)


def _results_dict(results: Union[Dict[str, Any], PathLike, Any]) -> Dict[str, Any]:
    """The results document: a dict, a lightsolver_results.Results (its ``doc``) or a file."""
    if isinstance(results, dict):
        return results
    doc = getattr(results, "doc", None)
    if isinstance(doc, dict):
        return doc
    from lightsolver_results import ResultsError, load

    try:
        return load(results)
    except ResultsError as exc:
        raise _report_error(str(exc)) from exc


def verifiable(results: Dict[str, Any]) -> bool:
    """True when the results record the scene content they were traced from (results written
    before provenance was recorded, or traced from a scene built in memory, do not)."""
    provenance = results.get("provenance")
    return isinstance(provenance, dict) and bool(provenance.get("scene_sha256"))


def differences(scene_path: PathLike, results: Union[Dict[str, Any], PathLike, Any]) -> List[str]:
    """One sentence per difference between the scene file and the scene the results were traced
    from (empty: they belong together); ReportError when the solver module is missing or the
    scene file cannot be read."""
    doc = _results_dict(results)
    try:
        import lightsolver
    except ImportError as exc:
        raise _report_error(f"the results cannot be checked against the scene without the "
                            f"lightsolver module ({exc}); build it (cmake --build)") from exc
    try:
        return list(lightsolver.verify_results(os.fspath(scene_path), doc))
    except ValueError as exc:  # lightsolver.InputError: an unreadable scene or provenance
        raise _report_error(str(exc)) from exc


def check(scene_path: PathLike, results: Union[Dict[str, Any], PathLike, Any], *,
          allow_unverified: bool = False) -> None:
    """Raise ReportError unless ``results`` belong to the scene file ``scene_path``: the scene's
    content and every file it reads (meshes, photometric files, the requirements table) as they
    were when the results were traced. Results that cannot be verified (no provenance, or a
    scene built in memory) are refused too, unless ``allow_unverified``."""
    doc = _results_dict(results)
    if allow_unverified and not verifiable(doc):
        return
    found = differences(scene_path, doc)
    if not found:
        return
    name = os.path.basename(os.fspath(scene_path))
    if not verifiable(doc):
        why = ("they were calculated from a model built or changed in memory, not from a saved "
               "model file" if isinstance(doc.get("provenance"), dict) else
               "they do not record which model they were calculated from (results of an older "
               "solver, or edited)")
        raise _report_error(f"the results cannot be verified against the model {name}: {why}. "
                            "Calculate again, or allow unverified results explicitly")
    raise _report_error(
        f"the results do not belong to the model {name}, so a report of them would be wrong: "
        + "; ".join(found) + ". Calculate again with the model as it is now")
