# SPDX-License-Identifier: LGPL-2.1-or-later
"""Calculation reports of an analysis (App code, headless): the results stored in the document
and the scene file they were computed from, rendered by the solver's report generator
``lightsolver_report`` (NativeSolver/python/lightsolver_report, docs/report.md) as HTML or PDF.
The report refuses what the generator refuses (broken, empty or cancelled results, results of
another scene, a missing output folder) and, what only the workbench knows, results that no
longer describe the model (stale) unless the caller accepts them (``allow_stale``); those are
then marked stale among the warnings, as is a scene file that had to be exported again.

The report gets the results **as traced** (every control group at 100 %, whatever light scene
the 3D view shows) and every light scene of the analysis as the document holds it now, which
the generator rescales from that one run (a page per scene); the analysis' report inputs
(objects/report_settings.py: project, sign-off names, date, energy) reach it as the scene's
``metadata.report``, so the scene file on disk, whose hash the results record, is not changed.

Two steps, so that the GUI can write on a worker thread (commands/report.py):
:func:`prepare_report` reads the document (main thread) into a :class:`ReportJob`, whose
:meth:`ReportJob.write` touches only files and the generator. :func:`make_report` does both.
(Not ``lighting/report.py``: that submodule would shadow the function ``lighting.report``.)"""
from __future__ import annotations

import json
import os
import sys
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any, Dict, List, Optional

from lighting.messages import CheckError, LightingError, Report, SolverUnavailableError

PACKAGE = "lightsolver_report"


class StaleResultsError(LightingError):
    """The stored results no longer describe the model; the report is refused unless the
    caller accepts them (``allow_stale=True``: then marked stale)."""

    def __init__(self, analysis_label: str, state_text: str) -> None:
        self.state_text = state_text
        super().__init__(f"Analysis '{analysis_label}': the {state_text}. Run the analysis "
                         "again before writing the report, or write it marked stale "
                         "(lighting.report(..., allow_stale=True)).")


class PartialResultsError(LightingError):
    """The stored results are those of a cancelled run; refused unless ``allow_partial``."""


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


def signoff_of(doc: Any) -> Dict[str, str]:
    """The sign-off fields the document knows: the project is its label, the author who
    created it (FreeCAD's document properties CreatedBy and Company); who checked it no
    document property says."""
    created = str(getattr(doc, "CreatedBy", "") or getattr(doc, "LastModifiedBy", "") or "")
    company = str(getattr(doc, "Company", "") or "")
    author = ", ".join(part.strip() for part in (created, company) if part.strip())
    return {"project": str(doc.Label), "author": author, "checked_by": ""}


@dataclass
class ReportJob:
    """One report to write, read from the document on the main thread. :meth:`write` reads no
    document object, so it may run on a worker thread (:meth:`start`)."""

    scene_file: str
    data: Dict[str, Any]
    path: str
    #: Keys merged into the scene's ``metadata`` for the report (``report``, ``light_scenes``); the file itself is left as the run read it.
    metadata: Dict[str, Any] = field(default_factory=dict)
    date: Optional[str] = None
    title: Optional[str] = None
    signoff: Dict[str, str] = field(default_factory=dict)
    view_png: Optional[str] = None
    allow_partial: bool = False
    allow_unverified: bool = False
    #: The user asked for stale results: what differs from the scene file goes on the page.
    allow_stale: bool = False
    #: Set by :meth:`write`: the path written, or the error (a LightingError) it raised.
    written: Optional[str] = None
    error: Optional[BaseException] = None
    _thread: Any = None

    def write(self) -> str:
        """Render and write the report; returns the path. Raises LightingError."""
        module = report_module()
        try:
            self.written = str(module.render(
                self.scene(), self.data, self.path, scene_path=self.scene_file,
                date=self.date, title=self.title,
                view_png=self.view_png, allow_partial=self.allow_partial,
                signoff=self.signoff, allow_unverified=self.allow_unverified,
                allow_stale=self.allow_stale))
        except module.ReportError as exc:
            raise LightingError(f"The report cannot be written: {exc}") from exc
        except OSError as exc:
            raise LightingError(f"The report cannot be written to '{self.path}': {exc}") from exc
        return self.written

    def scene(self) -> Dict[str, Any]:
        """The scene file's content with :attr:`metadata` merged into its ``metadata``
        (``report`` key by key). LightingError when the file cannot be read."""
        try:
            with open(self.scene_file, encoding="utf-8") as stream:
                scene = json.load(stream)
        except (OSError, ValueError) as exc:
            raise LightingError(f"The report cannot be written: the scene file "
                                f"'{self.scene_file}' cannot be read: {exc}") from exc
        if not isinstance(scene, dict):
            raise LightingError(f"The report cannot be written: '{self.scene_file}' is not a "
                                "scene")
        meta = dict(scene.get("metadata") or {})
        for key, value in self.metadata.items():
            if key == "report" and isinstance(meta.get("report"), dict):
                value = dict(meta["report"], **value)
            meta[key] = value
        scene["metadata"] = meta
        return scene

    # -- worker thread (the GUI polls ``finished``, as for an analysis run) -----------------
    def start(self) -> None:
        """Run :meth:`write` on a worker thread; poll :attr:`finished`, then read
        :attr:`written` or :attr:`error`."""
        import threading

        def worker() -> None:
            try:
                self.write()
            except BaseException as exc:  # noqa: BLE001 - reported on the main thread
                self.error = exc
        self._thread = threading.Thread(target=worker, name="lighting-report", daemon=True)
        self._thread.start()

    @property
    def finished(self) -> bool:
        """True when the worker thread ended (or never started)."""
        return self._thread is None or not self._thread.is_alive()

    def wait(self, timeout: Optional[float] = None) -> bool:
        """Join the worker thread; True if it ended."""
        if self._thread is not None:
            self._thread.join(timeout)
        return self.finished


def light_scenes_of(analysis: Any, notes: List[str]) -> List[Dict[str, Any]]:
    """The analysis' light scenes as the document holds them now, for the report's pages
    ({name, levels}, the scene format's ``metadata.light_scenes``); a scene whose levels do
    not pair up is left out and said in ``notes`` (Check names it too)."""
    from lighting.objects import light_scene

    found = []
    for scene in light_scene.scenes(analysis):
        try:
            found.append({"name": scene.Label, "levels": light_scene.levels(scene)})
        except ValueError as exc:
            notes.append(f"Light scene {scene.Label} is not shown: {exc}")
    return found


def _calculated_on(traced: Dict[str, Any]) -> Optional[str]:
    """When the run ended (its provenance's UTC time), or None when the results do not say."""
    from lighting.objects import results as results_obj

    typed = results_obj.read(traced)
    provenance = getattr(typed, "provenance", None) if typed is not None else None
    return getattr(provenance, "finished_utc", None) or None


def prepare_report(analysis: Any, path: str, date: Optional[str] = None,
                   title: Optional[str] = None, *, allow_stale: bool = False,
                   allow_partial: bool = False, allow_unverified: bool = False,
                   signoff: Optional[Dict[str, Any]] = None,
                   view_png: Optional[str] = None) -> ReportJob:
    """Read what the report of ``analysis``' stored results needs (main thread), refusing
    early what the document alone can tell: no results (CheckError), stale results unless
    ``allow_stale`` (StaleResultsError), partial results unless ``allow_partial``
    (PartialResultsError), an output folder that does not exist or a wrong suffix, report
    inputs that cannot be used (LightingError naming the property).

    The report gets the results as traced and the analysis' light scenes (the generator
    rescales each); its inputs come from the analysis' Report properties
    (objects/report_settings.py): ``title`` defaults to ProjectName, else the document's
    label; ``date`` to the ReportDate policy; the sign-off fields are the document's
    (:func:`signoff_of`), overridden by the analysis' names, overridden by ``signoff``."""
    from lighting.objects import report_settings
    from lighting.objects import results as results_obj
    from lighting.solver import store

    obj = store.results_object(analysis)
    data = results_obj.traced(obj)
    if data is None:
        raise CheckError(Report.one("error", f"Analysis '{analysis.Label}' has no results to "
                                             "report: run the analysis first"))
    module = report_module()
    try:
        module.guard.output_path(path)
    except module.ReportError as exc:
        raise LightingError(f"The report cannot be written: {exc}") from exc
    metadata = report_settings.metadata(analysis)  # unusable inputs refused before any work
    if not date:
        calculated = (_calculated_on(data) if getattr(analysis, "ReportDate", "") ==
                      "Calculation" else None)
        date = report_settings.report_date(analysis, calculated)
    state = store.results_state(analysis)
    if state.stale and not allow_stale:
        raise StaleResultsError(analysis.Label, state.text())
    if module.guard.is_partial(data) and not allow_partial:
        raise PartialResultsError(
            f"Analysis '{analysis.Label}': the results are partial (the run was cancelled "
            f"after {int(data.get('photons') or 0):,} photons). Run the analysis to the end, or "
            "write the report marked partial (lighting.report(..., allow_partial=True)).")
    notes: List[str] = []
    scene_file = _scene_file(analysis, obj.SceneFile, notes)
    if state.stale:
        notes.append(f"These {state.text()}: run the analysis again before handing this "
                     "report on.")
    metadata["light_scenes"] = light_scenes_of(analysis, notes)
    fields = dict(signoff_of(analysis.Document), **report_settings.signoff(analysis))
    fields.update({k: v for k, v in (signoff or {}).items() if v is not None})
    return ReportJob(scene_file=scene_file,
                     data=dict(data, warnings=list(data.get("warnings", [])) + notes),
                     path=path, metadata=metadata, date=date,
                     title=title or fields.get("project") or analysis.Document.Label,
                     signoff=fields, view_png=view_png, allow_partial=allow_partial,
                     allow_unverified=allow_unverified, allow_stale=allow_stale)


def make_report(analysis: Any, path: str, date: Optional[str] = None,
                title: Optional[str] = None, **options: Any) -> str:
    """Write the report of ``analysis``'s stored results to ``path`` (``.html`` or ``.pdf``) and
    return the path (:func:`prepare_report`'s refusals and ``options``, then
    :meth:`ReportJob.write`). Raises CheckError without results, StaleResultsError,
    PartialResultsError, SolverUnavailableError without the generator, LightingError when it
    cannot write the report (the reason in the message)."""
    return prepare_report(analysis, path, date, title, **options).write()
