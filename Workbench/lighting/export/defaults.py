# SPDX-License-Identifier: LGPL-2.1-or-later
"""The scene format tag and the solver's material defaults (docs/scene-format.md).

They are defined once, in the solver (NativeSolver/include/lightsolver/defaults.hpp), and read
from the native module ``lightsolver`` (``SCENE_FORMAT``, ``material_defaults()``) when it can
be imported. A scene can also be exported where the solver is not installed (Check without the
solver, ``lighting.export_scene``), so the same values are written here as a fallback;
Tests/python/test_defaults.py fails when the two disagree."""
from __future__ import annotations

import copy
from types import ModuleType
from typing import Dict, Optional, Union

Value = Union[float, bool]

FALLBACK_SCENE_FORMAT = "lightsolver.scene/1"
FALLBACK_MATERIAL_DEFAULTS: Dict[str, Dict[str, Value]] = {
    "diffuse": {"reflectance": 0.5},
    "mirror": {"reflectance": 0.9},
    "glass": {"ior": 1.52, "transmittance": 1.0, "thin": False},
    "glossy": {"reflectance": 0.0, "specular": 0.5, "roughness": 0.2},
}


def _native() -> Optional[ModuleType]:
    from lighting.messages import SolverUnavailableError
    from lighting.solver import run

    try:
        return run.load_module()
    except SolverUnavailableError:
        return None


def scene_format() -> str:
    """``format`` of the scene files this workbench writes."""
    module = _native()
    return str(getattr(module, "SCENE_FORMAT", FALLBACK_SCENE_FORMAT))


def material_defaults() -> Dict[str, Dict[str, Value]]:
    """{material type: {key: value}} for the keys a scene file may leave out."""
    module = _native()
    native = getattr(module, "material_defaults", None)
    return native() if native is not None else copy.deepcopy(FALLBACK_MATERIAL_DEFAULTS)
