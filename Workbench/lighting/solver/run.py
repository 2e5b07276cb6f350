# SPDX-License-Identifier: LGPL-2.1-or-later
"""The only module that talks to the native solver ``lightsolver`` (pybind11).

Where the module is looked for, in order:
1. ``LIGHTSOLVER_PYTHONPATH`` (folders, separated by ``os.pathsep``);
2. the FreeCAD parameter ``BaseApp/Preferences/Mod/Lighting/SolverPath``;
3. the build folders of the source tree this workbench lives in
   (``<repo>/build*/NativeSolver/python``; the workbench is usually a symlink into it);
4. ``sys.path`` as it is (a ``.pth`` file written by scripts/install-workbench.sh).

API used (docs/scene-format.md): ``load_scene(path)``, ``solve(scene, photons=, seed=,
confidence=, threads=, backend=, progress=, cancel=)`` returning the results dictionary,
``CancelToken()``, ``backends()`` (the backend registry). ``solve`` releases the GIL, so it
runs on a worker thread while the GUI stays responsive."""
from __future__ import annotations

import glob
import importlib
import os
import sys
from types import ModuleType
from typing import Any, Callable, Dict, List, Optional, Tuple

from lighting.messages import SolverError, SolverUnavailableError

MODULE_NAME = "lightsolver"
ENV_PATH = "LIGHTSOLVER_PYTHONPATH"
ENV_CLI = "LIGHTSOLVER_CLI"
PARAM_GROUP = "User parameter:BaseApp/Preferences/Mod/Lighting"

ProgressFn = Callable[[int, int], bool]

_module: Optional[ModuleType] = None
_backend_names: Optional[List[str]] = None


def repository_root() -> str:
    """The source tree holding this workbench (symlinks resolved)."""
    here = os.path.realpath(__file__)  # <repo>/Workbench/lighting/solver/run.py
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(here))))


def _parameter_path() -> str:
    try:
        import FreeCAD

        return FreeCAD.ParamGet(PARAM_GROUP).GetString("SolverPath", "")
    except Exception:  # noqa: BLE001 - outside FreeCAD
        return ""


def _build_dirs() -> List[str]:
    root = repository_root()
    found = []
    for pattern in ("build*/NativeSolver/python", "build*/python", "build*"):
        found.extend(d for d in sorted(glob.glob(os.path.join(root, pattern))) if os.path.isdir(d))
    # Newest build first.
    return sorted(dict.fromkeys(found), key=lambda d: -_newest_module_mtime(d))


def _newest_module_mtime(directory: str) -> float:
    files = glob.glob(os.path.join(directory, f"{MODULE_NAME}*.so"))
    return max((os.path.getmtime(f) for f in files), default=0.0)


def candidate_dirs() -> List[str]:
    """Folders searched for ``lightsolver*.so`` before the plain ``sys.path``."""
    dirs: List[str] = []
    env = os.environ.get(ENV_PATH, "")
    dirs.extend(d for d in env.split(os.pathsep) if d)
    param = _parameter_path()
    if param:
        dirs.append(param)
    dirs.extend(d for d in _build_dirs() if _newest_module_mtime(d) > 0.0)
    return dirs


def load_module() -> ModuleType:
    """Import ``lightsolver`` (see the module doc for where it is looked for).

    Raises SolverUnavailableError with the folders searched."""
    global _module
    if _module is not None:
        return _module
    searched = candidate_dirs()
    for directory in searched:
        if glob.glob(os.path.join(directory, f"{MODULE_NAME}*")):
            if directory not in sys.path:
                sys.path.insert(0, directory)
            break
    try:
        _module = importlib.import_module(MODULE_NAME)
    except ImportError as exc:
        where = ", ".join(searched) if searched else "no build folder found"
        raise SolverUnavailableError(
            f"The native solver module '{MODULE_NAME}' cannot be imported ({exc}). Build it "
            f"(cmake --build build) and set {ENV_PATH} to the folder holding "
            f"{MODULE_NAME}.cpython-*.so, or run scripts/install-workbench.sh. "
            f"Searched: {where}") from exc
    return _module


def solver_available() -> Tuple[bool, str]:
    """(True, module file) if the solver can be imported, else (False, reason)."""
    try:
        module = load_module()
    except SolverUnavailableError as exc:
        return False, str(exc)
    return True, getattr(module, "__file__", MODULE_NAME)


def backend_names() -> Optional[List[str]]:
    """The backend names the solver accepts, "auto" first: ``lightsolver.backends()``, the
    registry of the backends this build has. None when the module cannot be imported or
    predates ``backends()``. Asked once per session (finding out loads the GPU drivers)."""
    global _backend_names
    if _backend_names is None:
        try:
            _backend_names = [str(b["name"]) for b in load_module().backends()]
        except (SolverUnavailableError, AttributeError):
            return None
    return list(_backend_names)


def make_cancel_token() -> Optional[Any]:
    """A ``lightsolver.CancelToken`` if the module has one, else None."""
    module = load_module()
    factory = getattr(module, "CancelToken", None)
    return factory() if factory is not None else None


def solve_file(scene_file: str, photons: int, seed: int, confidence: float, threads: int = 0,
               backend: str = "auto", progress: Optional[ProgressFn] = None,
               cancel: Optional[Any] = None,
               target_accuracy: Optional[float] = None) -> Dict[str, Any]:
    """Load ``scene_file`` and trace it; returns the solver's results dictionary. With
    ``target_accuracy``, ``photons`` is the budget and the solver stops at the goal.

    Raises SolverUnavailableError, or SolverError with the solver's own message."""
    module = load_module()
    try:
        scene = module.load_scene(scene_file)
    except Exception as exc:  # noqa: BLE001 - the solver's validation messages
        raise SolverError(f"The solver rejected the scene: {exc}") from exc
    kwargs: Dict[str, Any] = {"photons": int(photons), "seed": int(seed),
                              "confidence": float(confidence), "threads": int(threads),
                              "progress": progress, "cancel": cancel}
    if backend and backend != "auto":
        kwargs["backend"] = backend
    if target_accuracy:
        kwargs["target_accuracy"] = float(target_accuracy)
    try:
        results = module.solve(scene, **kwargs)
    except TypeError as exc:
        if "backend" in kwargs and "incompatible" in str(exc):
            raise SolverError(f"This lightsolver build cannot choose a backend; set the "
                              f"analysis' Backend to 'auto' ({exc})") from exc
        raise SolverError(f"The solver failed: {exc}") from exc
    except Exception as exc:  # noqa: BLE001
        raise SolverError(f"The solver failed: {exc}") from exc
    from lighting.solver.results import reader

    if not isinstance(results, dict) or results.get("format") != reader().FORMAT:
        raise SolverError(f"The solver returned no results (got {type(results).__name__})")
    return results


def cli_executable() -> Optional[str]:
    """Path of the ``lightsolver`` command-line program, if one is found."""
    env = os.environ.get(ENV_CLI)
    if env and os.path.isfile(env):
        return env
    root = repository_root()
    for pattern in ("build*/NativeSolver/cli/lightsolver", "build*/bin/lightsolver",
                    "build*/lightsolver"):
        for path in sorted(glob.glob(os.path.join(root, pattern))):
            if os.path.isfile(path) and os.access(path, os.X_OK):
                return path
    return None
