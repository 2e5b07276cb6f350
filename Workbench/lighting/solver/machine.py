# SPDX-License-Identifier: LGPL-2.1-or-later
"""One analysis run through the stages Check -> Prepare -> Solve -> Results.

Check and Prepare read the document (main thread). Solve only touches files and the native
module, so it may run on a worker thread (:meth:`AnalysisRun.start`) while the GUI polls
``progress`` and stays responsive; Cancel sets a flag the progress callback returns to the
solver and cancels its token. Results are applied on the main thread in one undo step, and
only after the solver succeeded, so a failure never damages the document.

The analysis' ``Status`` records outcomes only (done, partial results, check failed,
failed: ...): the stage in progress is :attr:`AnalysisRun.stage`, never written to the
document, so a file saved during a run or after a Check never says "checking". The fingerprint
of the model (export/fingerprint.py) is taken when the scene is exported, so edits made while
the solver runs leave the stored results marked stale."""
from __future__ import annotations

import json
import os
import threading
import time
from typing import Any, Callable, Dict, Optional

from lighting import files
from lighting.export import fingerprint as fingerprint_mod
from lighting.export import scene as scene_mod
from lighting.messages import CancelledError, CheckError, LightingError, Report, SolverError
from lighting.objects import analysis as analysis_mod
from lighting.solver import check as check_mod
from lighting.solver import decide as decide_mod
from lighting.solver import results as results_mod
from lighting.solver import run, store

STAGES = ("idle", "check", "prepare", "solve", "results", "done", "failed", "cancelled")
ProgressFn = Callable[[int, int], Any]


class AnalysisRun:
    """State and stages of one run. Create, then ``check()``, ``prepare()``, ``solve()`` (or
    ``start()`` + poll ``finished``), then ``apply()``."""

    def __init__(self, analysis: Any, output_dir: Optional[str] = None,
                 log: Optional[Callable[[str, str], None]] = None,
                 spare_core: bool = False, decide_limit_s: Optional[float] = None) -> None:
        """``spare_core``: with Threads = 0 (all cores), leave one core to the GUI.
        ``decide_limit_s``: the tracing seconds a decide run may add by itself to decide its
        requirements (solver/decide.py; None: the preference, 0: never)."""
        self.analysis = analysis
        self.output_dir = output_dir or scene_mod.default_output_directory(analysis)
        self.log = log or (lambda level, text: None)
        self.stage = "idle"
        self.report = Report()
        self.export: Optional[scene_mod.ExportResult] = None
        self._checked_export: Optional[scene_mod.ExportResult] = None
        self.scene_file = ""
        self.results_file = ""
        self.fingerprint: Optional[Dict[str, str]] = None
        self.data: Optional[Dict[str, Any]] = None
        self.error: Optional[BaseException] = None
        self.done = 0
        self.total = 0
        self.started = 0.0
        #: When the run was made (its Check starts right after) and when its results were
        #: stored: wall_seconds() is the whole run as the user waited for it.
        self.created = time.monotonic()
        self.ended: Optional[float] = None
        #: The photons the solver was allowed (Photons, or MaxPhotons with an accuracy goal).
        self.budget = 0
        #: Photons traced in all (a run that continued to decide traced twice).
        self.photons_traced = 0
        #: What deciding the first pass' undecided requirements takes (None: all decided).
        self.decide_plan: Optional[decide_mod.Plan] = None
        #: Whether the run went on by itself to decide them (within the limit).
        self.continued = False
        self._cancelled = False
        self._token: Optional[Any] = None
        self._thread: Optional[threading.Thread] = None
        # Settings copied on the main thread; the worker never reads the document.
        self._settings = {
            "photons": int(analysis.Photons), "seed": int(analysis.Seed),
            "confidence": float(analysis.Confidence),
            "threads": int(analysis.Threads) or (max(1, (os.cpu_count() or 1) - 1)
                                                 if spare_core else 0),
            "backend": str(analysis.Backend), "accuracy": float(analysis.TargetAccuracy),
            "max_photons": int(analysis.MaxPhotons),
            "decides": analysis_mod.decides(analysis),
            "decide_limit_s": decide_mod.limit_seconds() if decide_limit_s is None
            else max(float(decide_limit_s), 0.0),
        }

    # -- stages --------------------------------------------------------------------------
    def check(self, need_solver: bool = True) -> Report:
        """Check stage; raises CheckError when there are errors."""
        self.stage = "check"
        self.report, self._checked_export = check_mod.check_and_export(self.analysis,
                                                                        need_solver=need_solver)
        for message in self.report.messages:
            self.log(message.level, message.text)
        if not self.report.ok:
            self.stage = "failed"
            store.set_status(self.analysis, "check failed")
            raise CheckError(self.report)
        if self.analysis.Status in ("check failed", "export failed"):
            # The model was fixed: the status describes the stored results again.
            store.set_status(self.analysis, store.settled_status(self.analysis))
        return self.report

    def prepare(self, progress: Optional[Callable[[str], None]] = None) -> str:
        """Prepare stage: export the scene file; returns its path."""
        self.stage = "prepare"
        # The Check stage's native check exported this very scene a moment ago: write that one
        # rather than tessellating the model again (Check always runs first in a run).
        self.export = self._checked_export or scene_mod.build_scene(self.analysis, progress)
        self._checked_export = None
        # What this scene was made of; nothing can change the model between export and here.
        self.fingerprint = fingerprint_mod.of_analysis(self.analysis)
        for message in self.export.report.messages:
            self.log(message.level, message.text)
        self.report.merge(self.export.report)
        if not self.export.report.ok:
            self.stage = "failed"
            store.set_status(self.analysis, "export failed")
            raise CheckError(self.export.report)
        self.scene_file = scene_mod.write_scene(self.export, self.output_dir,
                                                str(self.analysis.MeshStorage))
        store.set_scene_file(self.analysis, self.scene_file)
        self.log("info", f"Scene written: {self.scene_file} ({self.export.triangle_count} "
                         f"triangles, {len(self.export.scene['meshes'])} meshes)")
        return self.scene_file

    def _progress(self, offset: int, outer: Optional[ProgressFn]) -> ProgressFn:
        def callback(done: int, total: int) -> bool:
            self.done = offset + int(done)
            self.total = max(self.total, offset + int(total))
            if outer is not None and outer(self.done, self.total) is False:
                self._cancelled = True
            return not self._cancelled
        return callback

    def _solve_once(self, photons: int, offset: int, outer: Optional[ProgressFn],
                    accuracy: Optional[float] = None) -> Dict[str, Any]:
        s = self._settings
        return results_mod.normalise(run.solve_file(
            self.scene_file, photons, s["seed"], s["confidence"], s["threads"], s["backend"],
            self._progress(offset, outer), self._token, accuracy))

    def solve(self, progress: Optional[ProgressFn] = None) -> Dict[str, Any]:
        """Solve stage (blocking; safe on a worker thread). With a target accuracy the solver's
        own stopping rule traces until every target's half-width is at most that fraction of its
        mean (or MaxPhotons run out: the solver warns), so the goal is met, not predicted."""
        self.stage = "solve"
        self.started = time.monotonic()
        s = self._settings
        self.results_file = os.path.join(os.path.dirname(self.scene_file),
                                         scene_mod.RESULTS_FILE)
        try:  # before tracing: an hour of work must not be lost to an unwritable folder
            files.check_writable(self.results_file, "results file")
        except OSError as exc:
            raise SolverError(str(exc)) from exc
        self._token = run.make_cancel_token()
        accuracy = s["accuracy"] if s["accuracy"] > 0.0 else None
        photons = s["max_photons"] if accuracy else s["photons"]
        self.total = self.budget = photons
        data = self._solve_once(photons, 0, progress, accuracy)
        facts = results_mod.read(data).run
        self.photons_traced = int(facts.photons)
        if s["decides"] and not accuracy:
            data = self._continue_to_decide(data, photons, progress)
            facts = results_mod.read(data).run
        if accuracy and not facts.partial:
            self.log("info", f"Target accuracy {accuracy:g}: traced {facts.photons} "
                             f"photons (at most {photons})")
            self._rewrite_photons(facts.photons)
        elif facts.stop_reason == "decided" and facts.photons < photons:
            self.log("info", f"Decide: every requirement decided after {facts.photons:,} of "
                             f"at most {photons:,} photons")
        if self._cancelled and facts.photons <= 0:
            raise CancelledError("The analysis was cancelled before any photon was traced")
        self.data = data
        try:
            files.write_text(self.results_file, json.dumps(data, indent=1))
        except OSError as exc:
            raise SolverError(str(exc)) from exc
        return data

    def _continue_to_decide(self, data: Dict[str, Any], photons: int,
                            progress: Optional[ProgressFn]) -> Dict[str, Any]:
        """A decide run that spent its budget undecided traces again with the Decide budget
        (solver/decide.py) when that takes at most the limit; the second run replaces the
        first (same seed: its first photons are the first run's). Beyond the limit it stops
        and logs why."""
        facts = results_mod.read(data).run
        if facts.partial or self._cancelled or facts.stop_reason == "decided":
            return data
        plan = decide_mod.plan(results_mod.AnalysisResult.from_data(data))
        self.decide_plan = plan
        if plan is None:
            return data
        limit = self._settings["decide_limit_s"]
        count = f"{len(plan.undecided)} requirement(s) undecided after {facts.photons:,} photons"
        if not plan.within(limit):
            self.log("info", f"Decide: {count}; {why_not(plan, limit)}")
            return data
        self.log("info", f"Decide: {count}: tracing again with a budget of {plan.budget:,} "
                         f"photons (at most about {plan.seconds:.1f} s, within the {limit:g} s "
                         "a run continues by itself)")
        self.total = photons + plan.budget
        self.budget = plan.budget
        # The scene file says the budget before it is traced: the results' provenance hashes
        # the file as traced, so the CLI reproduces the run and the report accepts it.
        first_scene = self._rewrite_photons(plan.budget)
        again = self._solve_once(plan.budget, photons, progress)
        found = results_mod.read(again).run
        self.photons_traced += int(found.photons)
        if found.partial and found.photons < facts.photons:
            # Cancelled early in the second pass: the first is worth more, with its scene file.
            files.write_text(self.scene_file, first_scene)
            return data
        self.continued = True
        return again

    def _rewrite_photons(self, photons: int) -> str:
        """Make the scene file's settings say ``photons``; returns the file's former text."""
        with open(self.scene_file, encoding="utf-8") as stream:
            text = stream.read()
        scene = json.loads(text)
        scene.setdefault("settings", {})["photons"] = int(photons)
        files.write_text(self.scene_file, scene_mod.dumps_scene(scene))
        return text

    def apply(self) -> results_mod.AnalysisResult:
        """Results stage (main thread): store the results in the document."""
        if self.data is None:
            raise LightingError("No results to apply: the solve stage did not finish")
        self.stage = "results"
        result = store.apply_to_document(self.analysis, self.data, self.scene_file,
                                         self.results_file, self.fingerprint)
        for warning in result.warnings:
            self.log("warning", f"Solver: {warning}")
        self.stage = "cancelled" if result.partial else "done"
        self.ended = time.monotonic()
        return result

    # -- worker thread -------------------------------------------------------------------
    def start(self) -> None:
        """Run :meth:`solve` on a worker thread; poll :attr:`finished`, then :meth:`apply`."""
        def worker() -> None:
            try:
                self.solve()
            except BaseException as exc:  # noqa: BLE001 - reported on the main thread
                self.error = exc
        self.stage = "solve"
        self._thread = threading.Thread(target=worker, name="lightsolver", daemon=True)
        self._thread.start()

    def wall_seconds(self) -> float:
        """Seconds from the run's start (Check) to its results stored (or now)."""
        return (self.ended if self.ended is not None else time.monotonic()) - self.created

    @property
    def finished(self) -> bool:
        """True when the worker thread ended (or never started)."""
        return self._thread is None or not self._thread.is_alive()

    def wait(self, timeout: Optional[float] = None) -> bool:
        """Join the worker thread; True if it ended."""
        if self._thread is not None:
            self._thread.join(timeout)
        return self.finished

    def cancel(self) -> None:
        """Ask the solver to stop; it returns the photons traced so far (partial results)."""
        self._cancelled = True
        token = self._token
        if token is not None and hasattr(token, "cancel"):
            token.cancel()

    @property
    def cancelled(self) -> bool:
        """True once :meth:`cancel` was called."""
        return self._cancelled

    def fail(self, exc: BaseException) -> str:
        """Record a failure in the analysis' Status; returns the message for the user."""
        self.stage = "cancelled" if isinstance(exc, CancelledError) else "failed"
        text = str(exc) if isinstance(exc, LightingError) else f"{type(exc).__name__}: {exc}"
        try:
            store.set_status(self.analysis, "cancelled" if self.stage == "cancelled"
                             else f"failed: {text.splitlines()[0][:200]}")
        except Exception:  # noqa: BLE001 - the analysis may have been deleted meanwhile
            pass
        return text


def why_not(plan: decide_mod.Plan, limit_s: float) -> str:
    """Why a run did not go on to decide: "deciding needs up to 4.1 M photons, about 38 s,
    more than the 30 s a run continues by itself: press Decide"."""
    if plan.undecidable:
        return ("a value sits exactly on its requirement, so no run can decide it; "
                "the run stopped")
    need = f"deciding needs up to {decide_mod.photons_text(plan.budget)} photons"
    if plan.seconds is None:
        return need + " (the results give no tracing rate): press Decide"
    need += f", about {plan.seconds:.0f} s" if plan.seconds >= 10 else \
        f", about {plan.seconds:.1f} s"
    if limit_s <= 0.0:
        return need + " (runs do not continue by themselves: preference DecideLimitSeconds " \
                      "is 0): press Decide"
    return need + f", more than the {limit_s:g} s a run continues by itself: press Decide"


def run_analysis(analysis: Any, output_dir: Optional[str] = None,
                 progress: Optional[ProgressFn] = None,
                 log: Optional[Callable[[str, str], None]] = None,
                 decide_limit_s: Optional[float] = None) -> results_mod.AnalysisResult:
    """All four stages synchronously (headless API). Raises a LightingError subclass.
    ``decide_limit_s``: see :class:`AnalysisRun`."""
    job = AnalysisRun(analysis, output_dir, log, decide_limit_s=decide_limit_s)
    job.check()
    job.prepare()
    try:
        job.solve(progress)
    except (SolverError, CancelledError, run.SolverUnavailableError) as exc:
        job.fail(exc)
        raise
    except Exception as exc:  # noqa: BLE001 - unexpected: keep the message
        raise SolverError(job.fail(exc)) from exc
    return job.apply()
