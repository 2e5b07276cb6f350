# SPDX-License-Identifier: LGPL-2.1-or-later
"""Live results: a background solve that refines while the model is edited (docs/live.md).

:class:`LiveSession` exports the analysis once, builds a ``lightsolver.Simulation`` and refines
it on a worker thread in growing batches (photon totals doubling), publishing a
:class:`LiveFrame` after each, until the analysis' goal is reached (its TargetAccuracy, else its
verdicts when it decides, else its Photons); then it idles. A change to the document
(debounced, ``debounce_s``) restarts it doing the least work:

- only luminaires changed (moved, aimed, re-fluxed, another photometric file), the same ones
  in the same order: ``Simulation.set_luminaire`` for each changed one, no re-export;
- only furniture moved (placements; see :func:`_furniture`): ``Simulation.set_mesh_transform``
  of its meshes (instances), no re-export;
- anything else (geometry, materials, targets, settings, a luminaire added or removed):
  re-export and a new Simulation.

The worker never reads the document: everything it needs is read on the main thread by
:meth:`LiveSession.poll` (called by :meth:`next_frame` while it waits, or by the GUI's timer).
Every frame carries the model revision it was traced for; a frame of an older revision than
the session's is dropped where it is made and again where it is delivered, and nothing is
delivered while a change waits for its debounce, so a stale batch is never shown. Dimming and
light scenes are luminaire updates for now: the place where they will become a rescale without
tracing is :meth:`LiveSession._luminaire_updates`."""
from __future__ import annotations

import math
import os
import queue
import threading
import time
from dataclasses import dataclass, field
from typing import Any, Dict, Iterator, List, Optional, Tuple

from lighting.export import fingerprint as fingerprint_mod
from lighting.export import scene as scene_mod
from lighting.messages import CheckError, Report, SolverError
from lighting.objects import luminaire as luminaire_mod
from lighting.objects import luminaire_layout as layout_mod
from lighting.solver import results as results_mod
from lighting.solver import run

#: Photons of the first batch after a change (the first numbers, in a fraction of a second).
FIRST_PHOTONS = 1 << 15
#: Quiet time after the last document change before the session acts on it (dragging).
DEBOUNCE_S = 0.15


@dataclass
class LiveFrame:
    """One published state of the live solve."""

    revision: int  #: the model revision the photons were traced for
    data: Dict[str, Any]  #: normalised results (lightsolver.results/1 layout)
    photons: int
    worst_cell_relative: float  #: largest CI half-width / mean over cells and targets
    undecided: int  #: targets with requirements whose verdict is still undecided
    finished: bool  #: the goal is reached: the session idles until the next change
    path: str  #: how the scene was brought up to date: "export" or "luminaires"
    seconds_since_change: float  #: from the change (or the start) to this frame
    result: Optional[results_mod.AnalysisResult] = field(default=None, repr=False)
    #: ``data`` as the results reader reads it (lightsolver_results.Results)
    typed: Any = field(default=None, repr=False)


@dataclass
class _Command:
    revision: int
    path: str
    goal: Dict[str, Any]
    changed_at: float
    scene_text: str = ""
    movable_meshes: List[str] = field(default_factory=list)
    updates: List[Tuple[int, Dict[str, Any]]] = field(default_factory=list)
    moves: List[Tuple[int, List[List[float]]]] = field(default_factory=list)


@dataclass
class _Furniture:
    """An exported object the session can move as an instance: its meshes, its global
    placement when exported and its placement-free entry (export/fingerprint.py)."""

    meshes: List[int]
    placement: Any
    local: str


def worst_cell_relative(found: Any) -> float:
    """The largest relative CI half-width over grid cells and targets of ``found`` (the
    reader's ``lightsolver_results.Results``), the number shown as "worst cell +-%": a cell
    darker than 1 % of its grid's mean is judged against that 1 %, as the solver's per-cell
    accuracy goal does (docs/accuracy.md); infinity while a target has no light yet."""
    worst = 0.0
    for tgt in found.targets:
        target_mean = tgt.em.value or 0.0
        cells = tgt.cell_values
        rows = list(zip(cells.lux, cells.ci_low_lux, cells.ci_high_lux))
        rows.append((target_mean, tgt.em.low, tgt.em.high))
        for mean, low, high in rows:
            if low is None or high is None:
                continue
            floor = max(mean or 0.0, 0.01 * target_mean)
            if floor <= 0.0:
                return math.inf
            worst = max(worst, 0.5 * (high - low) / floor)
    return worst


def undecided_count(found: Any) -> int:
    """Targets of ``found`` (lightsolver_results.Results) whose requirements the solver could
    not yet judge pass or fail."""
    return sum(1 for t in found.targets if t.verdict == "undecided")


def _furniture(analysis: Any, export: Any) -> Dict[str, _Furniture]:
    """Exported objects that may move as instances: meshes (Mesh::Feature) and plain Part
    objects, not Arch elements (walls, slabs, windows: building, not furniture) and not objects
    a target refers to (a target's faces or cells would have to move with them)."""
    from lighting.export import collect
    from lighting.geometry import global_placement
    from lighting.objects import analysis as analysis_mod

    names = [m["name"] for m in export.scene["meshes"]]
    referred = {o.Name for tgt in analysis_mod.targets(analysis) for o in tgt.OutList}
    out: Dict[str, _Furniture] = {}
    for obj_name, meshes in export.object_meshes.items():
        obj = analysis.Document.getObject(obj_name)
        if obj is None or obj_name in referred or "IfcType" in obj.PropertiesList or \
                "IfcRole" in obj.PropertiesList:
            continue
        if not (collect.is_mesh(obj) or obj.isDerivedFrom("Part::Feature")):
            continue
        out[obj_name] = _Furniture([names.index(m) for m in meshes], global_placement(obj),
                                   fingerprint_mod.local_entry(obj))
    return out


class _Observer:
    """Marks the session dirty on any change to its document (main thread, App observer)."""

    def __init__(self, session: "LiveSession") -> None:
        self.session = session

    def slotChangedObject(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API)
        self.session._touched(obj, prop)

    def slotCreatedObject(self, obj: Any) -> None:  # noqa: N802
        self.session._touched(obj, "")

    def slotDeletedObject(self, obj: Any) -> None:  # noqa: N802
        self.session._touched(obj, "")


class LiveSession:
    """A live solve of one analysis (see the module doc). Use from the main thread::

        with lighting.LiveSession(doc) as live:      # stop() at the end
            for frame in live.frames(timeout=5.0):   # ends after 5 s without a new frame
                print(frame.photons, frame.worst_cell_relative)
                if frame.finished:
                    break
    """

    def __init__(self, doc: Any, analysis: Any = None, first_photons: int = FIRST_PHOTONS,
                 debounce_s: float = DEBOUNCE_S, threads: Optional[int] = None) -> None:
        from lighting.api import _analysis

        import FreeCAD

        self.analysis = _analysis(doc, analysis)
        self.doc = self.analysis.Document
        self.first_photons = int(first_photons)
        self.debounce_s = float(debounce_s)
        self._threads = threads
        self.revision = 0
        self.error: Optional[BaseException] = None
        self.latest: Optional[LiveFrame] = None
        self._dirty_at: Optional[float] = None
        self._cond = threading.Condition()
        self._command: Optional[_Command] = None
        self._stopped = False
        self._frames: "queue.Queue[LiveFrame]" = queue.Queue()
        self._sim: Any = None
        self._module = run.load_module()
        self._luminaires: List[Dict[str, Any]] = []
        self._furniture: Dict[str, _Furniture] = {}
        self._fingerprint: Dict[str, str] = {}
        self._paused = False  # the model stopped exporting: nothing traced until it does
        self._submit(self._export_command(time.monotonic()))
        self._observer = _Observer(self)
        FreeCAD.addDocumentObserver(self._observer)
        self._thread = threading.Thread(target=self._work, name="lighting-live", daemon=True)
        self._thread.start()

    # -- main thread -----------------------------------------------------------------------
    def _touched(self, obj: Any, prop: str) -> None:
        try:
            if obj.Document is not self.doc and obj.Document.Name != self.doc.Name:
                return
        except Exception:  # noqa: BLE001 - an object being deleted
            pass
        if prop in ("Status", "SceneFile") or obj.Name.startswith("LightingResults"):
            return  # the session's (or a run's) own writes, not the model
        self._dirty_at = time.monotonic()

    def _goal(self) -> Dict[str, Any]:
        a = self.analysis
        threads = self._threads if self._threads is not None else int(a.Threads)
        accuracy = float(a.TargetAccuracy)
        from lighting.objects import analysis as analysis_mod

        return {"seed": int(a.Seed), "confidence": float(a.Confidence),
                "accuracy": accuracy if accuracy > 0.0 else None,
                "decide": accuracy <= 0.0 and analysis_mod.decides(a),
                "photons": int(a.MaxPhotons) if accuracy > 0.0 else int(a.Photons),
                "threads": threads, "backend": str(a.Backend)}

    def _scene_luminaires(self) -> List[Dict[str, Any]]:
        lums = layout_mod.placed_luminaires(self.analysis, Report())
        return [luminaire_mod.scene_entry(lum) for lum in lums]

    def _export_command(self, changed_at: float) -> _Command:
        export = scene_mod.build_scene(self.analysis)
        if not export.report.ok:
            raise CheckError(export.report)
        self._luminaires = list(export.scene["luminaires"])
        self._fingerprint = fingerprint_mod.of_analysis(self.analysis)
        self._furniture = _furniture(self.analysis, export)
        movable = [export.scene["meshes"][i]["name"] for f in self._furniture.values()
                   for i in f.meshes]
        return _Command(self.revision, "export", self._goal(), changed_at,
                        scene_text=scene_mod.dumps_scene(export.scene), movable_meshes=movable)

    def _instance_moves(self, changed: List[str]) -> Optional[List[Tuple[int, List[List[float]]]]]:
        """The set_mesh_transform calls that bring the kept scene up to date when only
        furniture moved (placements changed, shapes and materials not), or None."""
        from lighting.geometry import global_placement

        if not changed or any(not key.startswith("object:") for key in changed):
            return None
        moves = []
        for key in changed:
            found = self._furniture.get(key.partition(":")[2])
            obj = self.doc.getObject(key.partition(":")[2])
            if found is None or obj is None or fingerprint_mod.local_entry(obj) != found.local:
                return None
            moved = global_placement(obj).multiply(found.placement.inverse()).toMatrix()
            rows = [[moved.A[4 * r + c] for c in range(4)] for r in range(4)]
            for r in range(3):
                rows[r][3] /= 1000.0  # mm -> m (the rotation part has no unit)
            moves.extend((mesh, rows) for mesh in found.meshes)
        return moves

    def _luminaire_updates(self, changed: List[str]) -> Optional[List[Tuple[int, Dict[str, Any]]]]:
        """The set_luminaire calls that bring the kept scene up to date when only luminaires
        changed, or None when the change needs an export. (A dimming or light-scene change
        will be a rescale here, with no tracing, once per-group contributions exist.)"""
        if not changed or any(not key.startswith("luminaire:") for key in changed):
            return None
        try:
            entries = self._scene_luminaires()
        except (OSError, ValueError):
            return None
        if [e["name"] for e in entries] != [e["name"] for e in self._luminaires]:
            return None
        updates = [(i, e) for i, (e, old) in enumerate(zip(entries, self._luminaires)) if e != old]
        self._luminaires = entries
        return updates

    def poll(self) -> bool:
        """Act on document changes once they have been quiet for ``debounce_s``; True when
        the session restarted. Main thread only (it reads the document)."""
        if self._dirty_at is None or time.monotonic() - self._dirty_at < self.debounce_s:
            return False
        changed_at, self._dirty_at = self._dirty_at, None
        current = fingerprint_mod.of_analysis(self.analysis)
        changed = [k for k in set(current) | set(self._fingerprint)
                   if current.get(k) != self._fingerprint.get(k)]
        if not changed and not self._paused:
            return False
        self.revision += 1
        kept = self._sim is not None  # else (a rejected scene) only an export will do
        updates = self._luminaire_updates(changed) if kept else None
        moves = self._instance_moves(changed) if kept and updates is None else None
        if updates is not None:
            self._fingerprint = current
            command = _Command(self.revision, "luminaires", self._goal(), changed_at,
                               updates=updates)
        elif moves is not None:
            self._fingerprint = current
            command = _Command(self.revision, "instances", self._goal(), changed_at,
                               moves=moves)
        else:
            try:
                command = self._export_command(changed_at)
            except CheckError as exc:
                # The model is being edited into shape: trace nothing until a change exports
                # again; the fingerprint stays the one of the kept scene, so that change is
                # compared with what the Simulation holds.
                self._submit(_Command(self.revision, "paused", self._goal(), changed_at))
                self.error, self._paused = exc, True
                return False
        self._submit(command)
        return True

    def _submit(self, command: _Command) -> None:
        self._paused = False  # (set again by poll() after a "paused" command)
        with self._cond:
            self._command = command
            self.error = None
            self._cond.notify_all()
        sim = self._sim
        if sim is not None:
            sim.cancel()  # the batch in progress is stale: end it now

    def next_frame(self, timeout: Optional[float] = None) -> Optional[LiveFrame]:
        """The next frame of the current revision (polling the document while waiting), or
        None after ``timeout`` seconds without one or once stopped. Raises the worker's error."""
        end = None if timeout is None else time.monotonic() + timeout
        while not self._stopped:
            self.poll()
            if self.error is not None and not isinstance(self.error, CheckError):
                raise self.error
            if self._dirty_at is not None:  # a change not acted on yet: frames may be stale
                time.sleep(0.02)
                continue
            try:
                frame = self._frames.get(timeout=0.02)
            except queue.Empty:
                if end is not None and time.monotonic() >= end:
                    return None
                continue
            if frame.revision == self.revision:  # an older one is stale: never delivered
                frame.result = results_mod.AnalysisResult.from_read(frame.typed, data=frame.data)
                self.latest = frame
                return frame
        return None

    def take_frame(self) -> Optional[LiveFrame]:
        """Non-blocking (the GUI's timer): acts on document changes, then returns the newest
        frame of the current revision waiting, or None."""
        self.poll()
        if self._dirty_at is not None:
            return None  # a change not acted on yet: what is queued may be stale
        newest = None
        while True:
            try:
                frame = self._frames.get_nowait()
            except queue.Empty:
                break
            if frame.revision == self.revision:
                newest = frame
        if newest is not None:
            newest.result = results_mod.AnalysisResult.from_read(newest.typed, data=newest.data)
            self.latest = newest
        return newest

    @property
    def fingerprint(self) -> Dict[str, str]:
        """The fingerprint of the model the current revision traces (export/fingerprint.py)."""
        return dict(self._fingerprint)

    def frames(self, timeout: Optional[float] = None) -> Iterator[LiveFrame]:
        """Successive frames until ``timeout`` seconds pass without one, or stop()."""
        while True:
            frame = self.next_frame(timeout)
            if frame is None:
                return
            yield frame

    def __iter__(self) -> Iterator[LiveFrame]:
        """``for frame in live``: frames until stop() (no timeout)."""
        return self.frames()

    def __enter__(self) -> "LiveSession":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.stop()

    def stop(self) -> None:
        """End the session: the worker stops after its batch; the observer is removed."""
        import FreeCAD

        with self._cond:
            self._stopped = True
            self._cond.notify_all()
        if self._sim is not None:
            self._sim.cancel()
        self._thread.join(timeout=30.0)
        try:
            FreeCAD.removeDocumentObserver(self._observer)
        except Exception:  # noqa: BLE001 - already removed
            pass

    @property
    def busy(self) -> bool:
        """True while the worker traces (the goal of the current revision not reached)."""
        latest = self.latest
        return not self._stopped and (latest is None or latest.revision != self.revision
                                      or not latest.finished)

    # -- worker thread ---------------------------------------------------------------------
    def _apply(self, command: _Command) -> None:
        if command.path == "export":
            self._sim = None
            scene = self._module.scene_from_json(command.scene_text,
                                                 os.path.dirname(self.doc.FileName or "") or ".")
            goal = command.goal
            backend = goal["backend"] if goal["backend"] else "auto"
            self._sim = self._module.Simulation(scene, backend=backend, threads=goal["threads"],
                                                movable_meshes=command.movable_meshes)
        elif command.path == "instances":
            for index, matrix in command.moves:
                self._sim.set_mesh_transform(index, matrix)
        else:
            for index, entry in command.updates:
                self._sim.set_luminaire(index, entry)

    def _work(self) -> None:
        command: Optional[_Command] = None
        total = 0
        finished = True
        while True:
            with self._cond:
                while not self._stopped and self._command is None and finished:
                    self._cond.wait()
                if self._stopped:
                    return
                fresh, self._command = self._command, None
            if fresh is not None and fresh.path == "paused":
                finished = True  # the model does not export: wait for the next change
                continue
            if fresh is not None:  # built outside the lock: a BVH takes a while
                command, total, finished = fresh, 0, False
                try:
                    self._apply(command)
                except self._module.InputError as exc:  # an edit the solver rejects: wait
                    report = Report()
                    report.add("error", f"The solver rejected the model: {exc}")
                    self.error = CheckError(report)
                    finished = True
                    continue
                except Exception as exc:  # noqa: BLE001 - reported on the main thread
                    self.error = SolverError(f"Live solve: {exc}")
                    finished = True
                    continue
            if command is None or self._sim is None:
                finished = True
                continue
            goal = command.goal
            total = min(max(2 * total, self.first_photons), goal["photons"])
            try:
                raw = self._sim.refine(total, seed=goal["seed"], confidence=goal["confidence"],
                                       target_accuracy=goal["accuracy"])
            except Exception as exc:  # noqa: BLE001
                self.error = SolverError(f"Live solve: {exc}")
                finished = True
                continue
            data = results_mod.normalise(raw)
            found = results_mod.read(data)
            if found.run.partial:
                continue  # cancelled for a change (or stop): the next command starts again
            undecided = undecided_count(found)
            finished = (found.run.photons >= goal["photons"]
                        or found.run.stop_reason == "accuracy"
                        or (goal["decide"] and undecided == 0))
            frame = LiveFrame(command.revision, data, found.run.photons,
                              worst_cell_relative(found), undecided, finished, command.path,
                              time.monotonic() - command.changed_at, typed=found)
            with self._cond:
                if self._command is None and command.revision == self.revision:
                    self._frames.put(frame)
