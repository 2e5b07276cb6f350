# SPDX-License-Identifier: LGPL-2.1-or-later
"""Lighting calculation reports (HTML and PDF) from a scene and its results.

Works from the solver boundary only: the scene JSON (docs/scene-format.md) and the results
JSON (docs/schemas/results.schema.json, with requirements and verdicts where the solver wrote
them). The CLI (``lightsolver report``), ``python3 -m lightsolver_report`` and the workbench
(``lighting.report``) all call :func:`render`, which refuses what does not belong in a report
(``guard.py``: results of another scene, broken or empty results, cancelled runs unless asked
for, a missing output folder) and writes the file whole or not at all. :func:`render_html` and
:func:`build` are its unchecked building blocks. See docs/report.md.

Libraries: Jinja2 (templates in ``templates/``, autoescaped), matplotlib (SVG pictures inside the
HTML), WeasyPrint (HTML to PDF). Same inputs, same date: byte-identical HTML."""
from __future__ import annotations

import datetime
import json
import os
from pathlib import Path
from typing import Any, Dict, Optional, Union

from lightsolver_report import fmt, guard
from lightsolver_report.guard import ReportError
from lightsolver_report.model import Report, build_report

__all__ = ["ReportError", "render", "render_html", "write_pdf", "build", "trace", "load_json",
           "report_date"]

PathLike = Union[str, "os.PathLike[str]"]
TEMPLATES = Path(__file__).resolve().parent / "templates"
#: Debian packages that provide what the report needs.
PACKAGES = {"jinja2": "python3-jinja2", "matplotlib": "python3-matplotlib",
            "weasyprint": "weasyprint", "lightsolver": "the lightsolver module (cmake --build)"}


def _require(name: str) -> Any:
    """Import a library or raise ReportError naming the Debian package to install."""
    import importlib

    try:
        return importlib.import_module(name)
    except ImportError as exc:
        raise ReportError(f"the report needs {name} ({exc}); install {PACKAGES[name]} "
                          f"(scripts/install-deps.sh)") from exc


def _solver() -> Optional[Any]:
    try:
        import lightsolver

        return lightsolver
    except ImportError:
        return None


def load_json(path: PathLike, what: str) -> Dict[str, Any]:
    """A JSON object from a file; ReportError naming the file otherwise."""
    try:
        with open(path, encoding="utf-8") as handle:
            data = json.load(handle)
    except (OSError, ValueError) as exc:
        raise ReportError(f"{path}: cannot read the {what}: {exc}") from exc
    if not isinstance(data, dict):
        raise ReportError(f"{path}: the {what} is not a JSON object")
    return data


def report_date(date: Union[None, str, datetime.date] = None) -> str:
    """The date printed on the report: ``date`` if given (ISO text or a date), else
    ``SOURCE_DATE_EPOCH`` (reproducible builds) in UTC, else today."""
    if isinstance(date, datetime.datetime):
        return date.date().isoformat()
    if isinstance(date, datetime.date):
        return date.isoformat()
    if date:
        try:
            return datetime.date.fromisoformat(str(date)).isoformat()
        except ValueError as exc:
            raise ReportError(f"date: expected YYYY-MM-DD (got {date!r})") from exc
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    if epoch:
        try:
            stamp = datetime.datetime.fromtimestamp(int(epoch), tz=datetime.timezone.utc)
        except (ValueError, OverflowError) as exc:
            raise ReportError(f"SOURCE_DATE_EPOCH: not a time stamp ({epoch!r})") from exc
        return stamp.date().isoformat()
    return datetime.date.today().isoformat()


def _settle_numpy_limits() -> None:
    """Let numpy measure its float limits before tracing: the Embree backend's TBB tasks run on
    the calling thread too and leave denormals flushed to zero there, after which numpy's first
    ``finfo`` (matplotlib asks for one) warns that the smallest subnormal is zero."""
    import numpy

    for kind in (numpy.float64, numpy.float32, numpy.longdouble, numpy.float16):
        numpy.finfo(kind)


def mpi_comm() -> Any:
    """MPI.COMM_WORLD when this process was started by an MPI launcher (``mpirun -np K
    lightsolver report``: every rank traces its share, docs/cluster.md), else None. Under a
    launcher without mpi4py or with a solver built without MPI: ReportError, since every rank
    would trace the whole scene and race to write the same report."""
    solver = _require("lightsolver")
    if not solver.mpi_launched():
        return None
    if not solver.mpi_built():
        raise ReportError("started by an MPI launcher, but this lightsolver was built without MPI")
    try:
        from mpi4py import MPI
    except ImportError as exc:
        raise ReportError("started by an MPI launcher, but mpi4py is missing (Debian: "
                          "python3-mpi4py)") from exc
    return MPI.COMM_WORLD


def reports_here() -> bool:
    """False on MPI ranks other than 0: they trace, rank 0 writes."""
    comm = mpi_comm()
    return comm is None or comm.Get_rank() == 0


def trace(scene_path: PathLike, photons: Optional[int] = None, seed: Optional[int] = None,
          confidence: Optional[float] = None, backend: str = "auto") -> Dict[str, Any]:
    """Trace a scene file through the ``lightsolver`` module with the scene's settings (the
    arguments override them); returns the results document without numpy arrays. Under an
    MPI launcher every rank traces its share of the same run (mpi_comm())."""
    solver = _require("lightsolver")
    _settle_numpy_limits()
    comm = mpi_comm()
    try:
        scene = solver.load_scene(str(scene_path))
        results = solver.solve(scene, photons=photons, seed=seed, confidence=confidence,
                               backend=backend, comm=comm)
    except ValueError as exc:  # lightsolver.InputError
        raise ReportError(str(exc)) from exc
    for target in results.get("targets", []):
        for key in [k for k in target if k.startswith("cells_") and k != "cells_uv"]:
            del target[key]  # the numpy arrays; "cells" holds the same numbers
    return results


def build(scene: Union[PathLike, Dict[str, Any]], results: Dict[str, Any], *,
          scene_path: Optional[PathLike] = None, date: Union[None, str, datetime.date] = None,
          title: Optional[str] = None, solver_version: Optional[str] = None,
          view_png: Optional[PathLike] = None,
          signoff: Optional[Dict[str, Any]] = None,
          annual: Union[None, PathLike, Dict[str, Any]] = None) -> Report:
    """The report's content (:class:`lightsolver_report.model.Report`) with its pictures.

    Besides what the scene and results give, the model carries what the caller adds:
    ``report.view_png`` (a false-colour picture of the model, absolute path, or None),
    ``report.signoff`` (project, author, checked_by; "" where not given) and
    ``report.partial`` (the results are a cancelled run's: every page says so) and
    ``report.annual`` (a year of daylight: ``annual``, an annual.json of ``lightsolver annual``
    or its dict, read by lightsolver_report.annual; None without). They are set before the
    pictures are drawn, which may use them."""
    from lightsolver_report import pictures, plots

    if not isinstance(scene, dict):
        scene_path = scene
        scene = load_json(scene, "scene")
    base_dir = os.path.dirname(os.path.abspath(scene_path)) if scene_path else os.getcwd()
    solver = _solver()
    if solver_version is None:
        solver_version = getattr(solver, "__version__", "unknown") if solver else "unknown"
    report = build_report(
        scene, results, scene_name=os.path.basename(str(scene_path)) if scene_path else "",
        base_dir=base_dir, date=report_date(date), solver_version=solver_version, title=title,
        photometry=solver.photometry_summary if solver else None,
        material_defaults=solver.material_defaults() if solver else None,
        sun_position=getattr(solver, "sun_position", None) if solver else None)
    report.view_png = guard.view_png(view_png)
    report.signoff = guard.signoff(signoff)
    report.partial = guard.is_partial(results)
    report.annual = annual_section(annual, scene)
    for i, area in enumerate(report.areas):
        if area.daylight is not None:
            daylight_pictures(area, i)
        elif area.grid is not None and area.grid.lux.size:
            area.plan_svg = plots.plan_svg(area.grid, f"plan{i}")
            area.chart_svg, area.chart_note = plots.chart_svg(area.grid, f"chart{i}")
    pictures.attach(report, scene, base_dir)
    return report


def annual_section(annual: Union[None, PathLike, Dict[str, Any]],
                   scene: Dict[str, Any]) -> Optional[Any]:
    """The annual section (lightsolver_report.annual.AnnualSection) with its plans, None
    without annual results; ReportError for annual results that cannot be read or are not of
    this scene."""
    if annual is None:
        return None
    from lightsolver_report import annual as annual_part

    meta = scene.get("metadata") if isinstance(scene.get("metadata"), dict) else {}
    labels = meta.get("labels") if isinstance(meta.get("labels"), dict) else {}
    try:
        section = annual_part.read_section(annual, scene, labels)
    except annual_part.AnnualError as exc:
        raise ReportError(str(exc)) from exc
    annual_part.attach_pictures(section)
    return section


def daylight_pictures(area: Any, index: int) -> None:
    """A daylight-factor grid's plan and value chart in percent (its cells' DF)."""
    import dataclasses

    from lightsolver_report import plots

    df = area.daylight
    if area.grid is None or df.percent is None or df.percent.shape != area.grid.lux.shape:
        return
    grid = dataclasses.replace(area.grid, lux=df.percent)
    area.plan_svg = plots.plan_svg(grid, f"dfplan{index}", quantity="D [%]")
    area.chart_svg, area.chart_note = plots.chart_svg(grid, f"dfchart{index}",
                                                      text=plots.df_text)


def render_html(scene: Union[PathLike, Dict[str, Any]], results: Dict[str, Any], *,
                scene_path: Optional[PathLike] = None,
                date: Union[None, str, datetime.date] = None, title: Optional[str] = None,
                solver_version: Optional[str] = None, view_png: Optional[PathLike] = None,
                signoff: Optional[Dict[str, Any]] = None,
                annual: Union[None, PathLike, Dict[str, Any]] = None) -> str:
    """The report as one self-contained HTML page (styles and SVG pictures inline). Unchecked:
    :func:`render` refuses results that do not belong before it calls this. ``annual``: an
    annual.json (or its dict) for the section "A year of daylight"."""
    jinja2 = _require("jinja2")
    report = build(scene, results, scene_path=scene_path, date=date, title=title,
                   solver_version=solver_version, view_png=view_png, signoff=signoff,
                   annual=annual)
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(str(TEMPLATES)), autoescape=True,
                             undefined=jinja2.StrictUndefined, trim_blocks=True,
                             lstrip_blocks=True, keep_trailing_newline=True)
    env.filters.update(fmt.FILTERS)
    return env.get_template("report.html.j2").render(
        report=report, css=(TEMPLATES / "report.css").read_text(encoding="utf-8"))


def write_pdf(html: str, out_path: PathLike) -> None:
    """Typeset the HTML page as a PDF (WeasyPrint), A4."""
    weasyprint = _require("weasyprint")
    import logging

    logging.getLogger("weasyprint").setLevel(logging.ERROR)  # font-subsetting chatter
    weasyprint.HTML(string=html, base_url=str(TEMPLATES)).write_pdf(str(out_path))


def render(scene: Union[PathLike, Dict[str, Any]], results: Union[None, PathLike, Dict[str, Any]],
           out_path: PathLike, *, scene_path: Optional[PathLike] = None,
           date: Union[None, str, datetime.date] = None, title: Optional[str] = None,
           solver_version: Optional[str] = None, photons: Optional[int] = None,
           seed: Optional[int] = None, backend: str = "auto",
           view_png: Optional[PathLike] = None, allow_partial: bool = False,
           signoff: Optional[Dict[str, Any]] = None, allow_unverified: bool = False,
           allow_stale: bool = False,
           annual: Union[None, PathLike, Dict[str, Any]] = None) -> Path:
    """Write the report of ``scene`` (a path, or a scene dict with ``scene_path`` naming where
    its relative files lie) to ``out_path``: ``.html``/``.htm`` or ``.pdf``.

    ``results``: a results dict or file; None traces the scene first (its settings; ``photons``,
    ``seed``, ``backend`` override them). ``date`` (YYYY-MM-DD) makes the output reproducible.
    ``view_png``: a false-colour picture of the model (PNG) for the report; ``signoff``:
    {project, author, checked_by} for the sign-off block. ``annual``: the annual.json of
    ``lightsolver annual`` for this scene (or its dict): the report gets its section "A year of
    daylight"; refused like the results (unreadable, breaking the annual schema, no grid, grids
    that are not the scene's).

    Refused with ReportError, before anything is written (docs/report.md, "What the report
    refuses"): an output folder that does not exist (it is never created) or another suffix;
    results that cannot be read, break the results schema or hold no targets; results of a
    cancelled run unless ``allow_partial`` (then every page says so); results that do not
    belong to the scene file (``provenance.check``; ``allow_unverified`` is passed to it;
    ``allow_stale``: results the caller knows to be of an earlier state of the model, written
    with what differs among the page's warnings instead of refused). The
    file is written whole or not at all: an error while writing leaves an old report as it was.
    Returns the path written."""
    out = guard.output_path(out_path)
    signoff = guard.signoff(signoff)
    annual = guard.annual_document(annual)
    view_png = guard.view_png(view_png)
    if not isinstance(scene, dict):
        scene_path = scene
    if results is None:
        if scene_path is None:
            raise ReportError("no results given and no scene file to trace")
        where = "the results traced now"
        results = guard.results_document(
            trace(scene_path, photons=photons, seed=seed, backend=backend), where)
    else:  # a file or a dict from elsewhere: does it belong to this scene?
        where = guard.describe(results)
        results = guard.results_document(results)
        differs = guard.check_provenance(scene_path, results, allow_unverified=allow_unverified,
                                         allow_stale=allow_stale)
        if differs:
            results = dict(results, warnings=list(results.get("warnings") or []) + [differs])
    if not allow_partial:
        guard.refuse_partial(results, where)
    html = render_html(scene, results, scene_path=scene_path, date=date, title=title,
                       solver_version=solver_version, view_png=view_png, signoff=signoff,
                       annual=annual)
    if guard.SUFFIXES[out.suffix.lower()] == "pdf":
        write = lambda temporary: write_pdf(html, temporary)  # noqa: E731
    else:
        write = lambda temporary: temporary.write_text(html, encoding="utf-8")  # noqa: E731
    try:
        return guard.write_atomically(out, write)
    except OSError as exc:
        raise ReportError(f"{out}: cannot write the report: {exc}") from exc
