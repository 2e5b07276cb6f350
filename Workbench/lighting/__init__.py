# SPDX-License-Identifier: LGPL-2.1-or-later
"""Lighting: architectural lighting analysis for FreeCAD (public scripting API).

Works headless (``freecadcmd``) and in the GUI::

    import FreeCAD, lighting
    doc = FreeCAD.openDocument("office.FCStd")
    result = lighting.analyze(doc)          # Check -> Prepare -> Solve -> Results
    print(result.table())                   # Em, Emin, Emax, U0 with their CIs
    result["Workplane"].mean_lux

Objects: :func:`make_analysis`, :func:`make_luminaire`, :func:`make_face_target`,
:func:`make_grid_target`, :func:`make_placement_domain`,
:func:`add_luminaire_layout`, :func:`make_observer`, :func:`make_light_scene`, :func:`make_sky`
(shown with :func:`show_light_scene`), :func:`make_annual_daylight` (a year of daylight, run by
:func:`run_annual`). Stages on their own:
:func:`check`, :func:`export_scene`, :func:`solver_available`. Model state: :func:`exclude`,
:func:`left_out`, :func:`results_state`. Errors derive from
:class:`LightingError` and carry a message meant for the user.

Attributes load lazily, so ``import lighting`` is cheap (FreeCAD imports it at start-up).
"""
from __future__ import annotations

import importlib
from typing import Any

__version__ = "0.1.0"

_EXPORTS = {
    "accuracy_study": "lighting.api",
    "add_luminaire_layout": "lighting.api",
    "analyze": "lighting.api",
    "check": "lighting.api",
    "exclude": "lighting.api",
    "export_scene": "lighting.api",
    "left_out": "lighting.api",
    "optimize_placement": "lighting.api",
    "report": "lighting.api",
    "results": "lighting.api",
    "results_state": "lighting.api",
    "solver_available": "lighting.api",
    "luminaire_library_entries": "lighting.api",
    "assign_photometry": "lighting.api",
    "AnalysisResult": "lighting.solver.results",
    "LiveFrame": "lighting.solver.live",
    "LiveSession": "lighting.solver.live",
    "TargetResult": "lighting.solver.results",
    "make_analysis": "lighting.objects.factory",
    "make_luminaire": "lighting.objects.factory",
    "make_face_target": "lighting.objects.factory",
    "make_grid_target": "lighting.objects.factory",
    "make_placement_domain": "lighting.objects.factory",
    "make_observer": "lighting.objects.factory",
    "make_light_scene": "lighting.objects.factory",
    "make_sky": "lighting.objects.factory",
    "make_annual_daylight": "lighting.objects.annual",
    "run_annual": "lighting.solver.annual",
    "show_light_scene": "lighting.objects.factory",
    "grid_spacing_m": "lighting.standards",
    "LightingError": "lighting.messages",
    "CheckError": "lighting.messages",
    "ExportError": "lighting.messages",
    "SolverError": "lighting.messages",
    "SolverUnavailableError": "lighting.messages",
    "CancelledError": "lighting.messages",
}

__all__ = sorted(_EXPORTS) + ["__version__"]


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'lighting' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list:
    return __all__
