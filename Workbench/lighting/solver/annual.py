# SPDX-License-Identifier: LGPL-2.1-or-later
"""One annual daylight run through the stages Check -> Prepare -> Solve -> Results, as
solver/machine.py runs an analysis (objects/annual.py; docs/workbench-daylight.md, "Annual
daylight").

Check and Prepare read the document (main thread): the analysis' checks (its electric
luminaires are not needed: the annual run traces daylight only), the annual object's, one Sky
and at least one grid; Prepare exports the scene as a run does, into ``<output>/annual``. Solve
calls ``lightsolver.annual`` on the scene file and the weather file (it releases the GIL, so it
runs on a worker thread) and writes ``annual.json`` and ``annual.npz`` beside the scene (the
CLI's layout: docs/daylight.md). Cancel stops the trace between its batches
(``lightsolver.annual``'s ``cancel`` token; the direct sun's shadow rays before it are not cut)
and drops the results, so a cancelled run never changes the document. Results are stored in one undo step."""
from __future__ import annotations

import hashlib
import io
import json
import os
import threading
import time
from typing import Any, Callable, Dict, Optional

from lighting import files
from lighting.export import daylight as daylight_mod
from lighting.export import fingerprint as fingerprint_mod
from lighting.export import scene as scene_mod
from lighting.messages import CancelledError, CheckError, LightingError, Report, SolverError
from lighting.objects import analysis as analysis_mod
from lighting.objects import annual as annual_mod
from lighting.objects import sky as sky_mod
from lighting.solver import check as check_mod
from lighting.solver import run, store

SUBFOLDER = "annual"
SUMMARY_FILE = "annual.json"
HOURS_FILE = "annual.npz"
#: The analysis' check that an annual run does not share: it needs no electric light.
NO_LUMINAIRES = "No luminaires"


def sha256_of(path: str) -> str:
    """The file's SHA-256 (hex), as the solver reports the weather file's."""
    digest = hashlib.sha256()
    with open(path, "rb") as stream:
        for block in iter(lambda: stream.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def model_fingerprint(analysis: Any) -> Dict[str, str]:
    """What the annual results depend on in the model: the analysis' fingerprint without its
    run settings and electric luminaires (the annual run has settings of its own and traces
    daylight only)."""
    return {k: v for k, v in fingerprint_mod.of_analysis(analysis).items()
            if k != "settings" and not k.startswith("luminaire:")}


def is_current(obj: Any) -> Optional[bool]:
    """Whether the stored results still describe the model and the weather file (None: no
    results)."""
    if not obj.SummaryJson:
        return None
    analysis = annual_mod.analysis_of(obj)
    stored = fingerprint_mod.loads(obj.InputsFingerprint)
    if analysis is None or stored is None or stored != model_fingerprint(analysis):
        return False
    path = str(obj.WeatherFile)
    return os.path.isfile(path) and sha256_of(path) == obj.WeatherSha256


#: How far (degrees of latitude or longitude) the weather file's station may lie from the
#: Sky's site before Check warns: about 100 km, a neighbouring city's airport.
SITE_TOLERANCE_DEG = 1.0


def site_mismatch(weather_file: str, site: Any) -> str:
    """Why the weather file seems to be another place's than the Sky's site ("" when it is
    near, or when its LOCATION line cannot be read: the solver reports a malformed file). The
    run takes the file's hours as they are, so a file of another city gives that city's year."""
    try:
        with open(weather_file, encoding="latin-1") as stream:
            fields = stream.readline().strip().split(",")
        lat, lon = float(fields[6]), float(fields[7])
    except (OSError, ValueError, IndexError):
        return ""
    if (abs(lat - site.latitude_deg) <= SITE_TOLERANCE_DEG and
            abs(lon - site.longitude_deg) <= SITE_TOLERANCE_DEG):
        return ""
    return (f"the weather file's station ({fields[1]}, {lat:.2f}, {lon:.2f}) is far from the "
            f"site ({site.source}: {site.latitude_deg:.2f}, {site.longitude_deg:.2f}); the year "
            "is the station's")


class AnnualRun:
    """State and stages of one annual run: ``check()``, ``prepare()``, ``solve()`` (or
    ``start()`` + poll ``finished``), then ``apply()``."""

    def __init__(self, annual: Any, output_dir: Optional[str] = None,
                 log: Optional[Callable[[str, str], None]] = None) -> None:
        self.annual = annual
        self.analysis = annual_mod.analysis_of(annual)
        if self.analysis is None:
            raise LightingError(f"'{annual.Label}' is in no analysis: put it in the analysis "
                                "whose Sky and grids it uses")
        base = output_dir or scene_mod.default_output_directory(self.analysis)
        self.output_dir = os.path.join(base, SUBFOLDER)
        self.log = log or (lambda level, text: None)
        self.stage = "idle"
        self.report = Report()
        self.scene_file = ""
        self.fingerprint: Optional[Dict[str, str]] = None
        self.result: Optional[Dict[str, Any]] = None
        self.error: Optional[BaseException] = None
        self.created = time.monotonic()
        self._cancelled = False
        self._token: Optional[Any] = None
        self._thread: Optional[threading.Thread] = None
        # Settings copied on the main thread; the worker never reads the document.
        self._settings: Dict[str, Any] = {}

    # -- stages --------------------------------------------------------------------------
    def check(self) -> Report:
        """Check stage; raises CheckError when there are errors."""
        self.stage = "check"
        base, _ = check_mod.check_and_export(self.analysis, need_solver=True)
        report = Report()
        for m in base.messages:
            if not (m.level == "error" and m.text.startswith(NO_LUMINAIRES)):
                report.add(m.level, m.text, m.object_name)
        report.extend(annual_mod.check(self.annual), self.annual.Name)
        skies = daylight_mod.skies(self.analysis)
        if len(skies) != 1:
            report.add("error", f"{self.annual.Label}: the analysis needs exactly one Sky (its "
                                f"windows' portals and site), it has {len(skies)}")
        grids = [t for t in analysis_mod.targets(self.analysis) if t.TargetType == "Grid"]
        if not grids:
            report.add("error", f"{self.annual.Label}: the analysis has no grid target: the "
                                "annual metrics are per grid cell")
        if report.ok and not hasattr(run.load_module(), "annual"):
            report.add("error", "This lightsolver build has no annual run: rebuild it")
        self.report = report
        for message in report.messages:
            self.log(message.level, message.text)
        if not report.ok:
            self.stage = "failed"
            self._set_status("check failed")
            raise CheckError(report)
        self._copy_settings(skies[0])
        far = site_mismatch(str(self.annual.WeatherFile), sky_mod.resolve_site(skies[0]))
        if far:
            report.add("warning", f"{self.annual.Label}: {far}", self.annual.Name)
            self.log("warning", far)
        return report

    def _copy_settings(self, sky: Any) -> None:
        obj = self.annual
        ground = float(obj.GroundReflectance)
        blinds = float(obj.BlindsTransmittance)
        self._settings = {
            "weather": str(obj.WeatherFile), "mf": annual_mod.mf(obj),
            "north_deg": sky_mod.resolve_site(sky).north_deg,
            "ground_reflectance": ground if ground >= 0.0 else None,
            "photons": int(obj.Photons), "seed": int(obj.Seed),
            "backend": str(self.analysis.Backend) or "auto",
            "threads": int(self.analysis.Threads), "confidence": float(obj.Confidence),
            "blinds_transmittance": blinds if blinds > 0.0 else None}

    def prepare(self) -> str:
        """Prepare stage: export the scene (as a run does) into ``<output>/annual``."""
        self.stage = "prepare"
        export = scene_mod.build_scene(self.analysis)
        self.fingerprint = model_fingerprint(self.analysis)
        for message in export.report.messages:
            self.log(message.level, message.text)
        self.report.merge(export.report)
        if not export.report.ok:
            self.stage = "failed"
            self._set_status("export failed")
            raise CheckError(export.report)
        self.scene_file = scene_mod.write_scene(export, self.output_dir,
                                                str(self.analysis.MeshStorage))
        self.log("info", f"Scene written: {self.scene_file}")
        return self.scene_file

    def solve(self) -> Dict[str, Any]:
        """Solve stage (blocking; safe on a worker thread): the year, then its files."""
        self.stage = "solve"
        s = dict(self._settings)
        weather = s.pop("weather")
        summary_path = os.path.join(self.output_dir, SUMMARY_FILE)
        try:  # before tracing: a minute of work must not be lost to an unwritable folder
            files.check_writable(summary_path, "annual results file")
        except OSError as exc:
            raise SolverError(str(exc)) from exc
        module = run.load_module()
        self._token = run.make_cancel_token()
        if self._token is not None:
            s["cancel"] = self._token
            if self._cancelled:
                self._token.cancel()
        try:
            result = module.annual(self.scene_file, weather, **s)
        except Exception as exc:  # noqa: BLE001 - the solver's own message names the field
            raise SolverError(f"The annual run failed: {exc}") from exc
        if self._cancelled:
            raise CancelledError("The annual run was cancelled: its results were dropped")
        try:
            files.write_text(summary_path, json.dumps(result["summary"], indent=1))
            files.write_bytes(os.path.join(self.output_dir, HOURS_FILE), _npz(result))
        except OSError as exc:
            raise SolverError(str(exc)) from exc
        self.result = result
        return result

    def apply(self) -> Dict[str, Any]:
        """Results stage (main thread): store the summary on the annual object (one undo
        step); returns the summary."""
        if self.result is None:
            raise LightingError("No annual results to apply: the solve stage did not finish")
        self.stage = "results"
        summary = self.result["summary"]
        from lighting import annual_results

        typed = annual_results.read(summary)
        if typed is None:
            raise SolverError("The annual run returned a summary the reader refuses")
        obj = self.annual
        with store.undo_step(obj.Document, "Annual daylight results"):
            obj.WeatherName = typed.weather.file
            obj.WeatherSha256 = typed.weather.sha256
            obj.NorthUsed = float(self._settings["north_deg"])
            obj.OutputFolder = self.output_dir
            obj.InputsFingerprint = fingerprint_mod.dumps(self.fingerprint or {})
            obj.SummaryJson = json.dumps(summary, separators=(",", ":"))
            obj.Status = "done"
        self.stage = "done"
        return summary

    # -- worker thread -------------------------------------------------------------------
    def start(self) -> None:
        """Run :meth:`solve` on a worker thread; poll :attr:`finished`, then :meth:`apply`."""
        def worker() -> None:
            try:
                self.solve()
            except BaseException as exc:  # noqa: BLE001 - reported on the main thread
                self.error = exc
        self.stage = "solve"
        self._thread = threading.Thread(target=worker, name="lightsolver-annual", daemon=True)
        self._thread.start()

    @property
    def finished(self) -> bool:
        return self._thread is None or not self._thread.is_alive()

    def wait(self, timeout: Optional[float] = None) -> bool:
        if self._thread is not None:
            self._thread.join(timeout)
        return self.finished

    def cancel(self) -> None:
        """Stop the trace at its next batch and drop the results."""
        self._cancelled = True
        if self._token is not None:
            self._token.cancel()

    def fail(self, exc: BaseException) -> str:
        """Record a failure in Status; returns the message for the user."""
        self.stage = "cancelled" if isinstance(exc, CancelledError) else "failed"
        text = str(exc) if isinstance(exc, LightingError) else f"{type(exc).__name__}: {exc}"
        self._set_status("cancelled" if self.stage == "cancelled"
                         else f"failed: {text.splitlines()[0][:200]}")
        return text

    def _set_status(self, text: str) -> None:
        try:
            if self.annual.Status != text:
                with store.undo_step(self.annual.Document, "Annual daylight status"):
                    self.annual.Status = text
        except Exception:  # noqa: BLE001 - the object may have been deleted meanwhile
            pass


def _npz(result: Dict[str, Any]) -> bytes:
    """annual.npz as the CLI writes it: per grid i ``g{i}_mean``, ``g{i}_low``, ``g{i}_high``
    and with a sun ``g{i}_direct_sun`` (hours x cells float32, lx), and ``month_day_hour``."""
    import numpy as np

    arrays = {"month_day_hour": np.asarray(result["month_day_hour"])}
    for i, grid in enumerate(result["grids"]):
        for key in ("mean", "low", "high", "direct_sun"):
            if grid.get(key) is not None:
                arrays[f"g{i}_{key}"] = np.asarray(grid[key], dtype=np.float32)
    buffer = io.BytesIO()
    np.savez_compressed(buffer, **arrays)
    return buffer.getvalue()


def run_annual(annual: Any, output_dir: Optional[str] = None,
               log: Optional[Callable[[str, str], None]] = None) -> Dict[str, Any]:
    """All four stages synchronously (headless API); returns the stored summary. Raises a
    LightingError subclass."""
    job = AnnualRun(annual, output_dir, log)
    job.check()
    job.prepare()
    try:
        job.solve()
    except LightingError as exc:
        job.fail(exc)
        raise
    except Exception as exc:  # noqa: BLE001 - unexpected: keep the message
        raise SolverError(job.fail(exc)) from exc
    return job.apply()
