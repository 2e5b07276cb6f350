# SPDX-License-Identifier: LGPL-2.1-or-later
"""Calculation reports of an analysis (App code, headless): the results stored in the document
and the scene file they were computed from, rendered by the solver's report generator
``lightsolver_report`` (NativeSolver/python/lightsolver_report, docs/report.md) as HTML or PDF.
The workbench adds nothing of its own to the report but two warnings it alone can give: results
that no longer describe the model (stale), and a scene file that had to be exported again.
(Not ``lighting/report.py``: that submodule would shadow the function ``lighting.report``.)"""
from __future__ import annotations

import os
import sys
from types import ModuleType
from typing import Any, List, Optional

from lighting.messages import CheckError, LightingError, Report, SolverUnavailableError

PACKAGE = "lightsolver_report"


def report_module() -> ModuleType:
    """Import ``lightsolver_report``: it lies beside the ``lightsolver`` module in a build
    (CMake copies it there), else in the source tree this workbench belongs to."""
    import importlib

    from lighting.solver import run

    run.load_module()  # puts the module's folder on sys.path
    try:
        return importlib.import_module(PACKAGE)
    except ImportError:
        source = os.path.join(run.repository_root(), "NativeSolver", "python")
        if not os.path.isfile(os.path.join(source, PACKAGE, "__init__.py")):
            raise SolverUnavailableError(
                f"The report generator '{PACKAGE}' is not found beside the lightsolver module "
                f"nor in {source}; build the project (cmake --build build)") from None
        sys.path.append(source)
        return importlib.import_module(PACKAGE)


def _scene_file(analysis: Any, stored: str, notes: List[str]) -> str:
    """The scene the results were computed from; exported again when it is gone."""
    if stored and os.path.isfile(stored):
        return stored
    from lighting.export.scene import build_scene, default_output_directory, write_scene

    result = build_scene(analysis)
    if not result.report.ok:
        raise CheckError(result.report)
    notes.append("The scene file of the run was not found; the model was exported again for "
                 "this report, so the scene shown may differ from the one traced.")
    folder = os.path.dirname(stored) if stored else default_output_directory(analysis)
    return write_scene(result, folder, analysis.MeshStorage)


def make_report(analysis: Any, path: str, date: Optional[str] = None,
                title: Optional[str] = None) -> str:
    """Write the report of ``analysis``'s stored results to ``path`` (``.html`` or ``.pdf``) and
    return the path. Raises CheckError without results, SolverUnavailableError without the
    generator, LightingError when it cannot write the report (the reason in the message)."""
    from lighting.objects import results as results_obj
    from lighting.solver import store

    obj = store.results_object(analysis)
    data = results_obj.data(obj)
    if data is None:
        raise CheckError(Report.one("error", f"Analysis '{analysis.Label}' has no results to "
                                             "report: run the analysis first"))
    notes: List[str] = []
    scene_file = _scene_file(analysis, obj.SceneFile, notes)
    state = store.results_state(analysis)
    if state.stale:
        notes.append(f"These {state.text()}: run the analysis again before handing this "
                     "report on.")
    data = dict(data, warnings=list(data.get("warnings", [])) + notes)
    module = report_module()
    try:
        written = module.render(scene_file, data, path, date=date,
                                title=title or analysis.Document.Label)
    except module.ReportError as exc:
        raise LightingError(f"The report cannot be written: {exc}") from exc
    except OSError as exc:
        raise LightingError(f"The report cannot be written to '{path}': {exc}") from exc
    return str(written)
