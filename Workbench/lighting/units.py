# SPDX-License-Identifier: LGPL-2.1-or-later
"""Unit conversion between FreeCAD (millimetres) and the scene format (metres)."""
from __future__ import annotations

from typing import Any, List

#: FreeCAD lengths are millimetres; the scene format uses metres.
MM_TO_M = 0.001
M_TO_MM = 1000.0


def vec_m(vector_mm: Any) -> List[float]:
    """A FreeCAD vector in millimetres as a ``[x, y, z]`` list in metres (rounded to 1 nm,
    which removes float noise like 0.9500000000000001)."""
    return [round(vector_mm.x * MM_TO_M, 9), round(vector_mm.y * MM_TO_M, 9),
            round(vector_mm.z * MM_TO_M, 9)]
