# SPDX-License-Identifier: LGPL-2.1-or-later
"""EN 12464-1 calculation-grid rules (pure Python, no FreeCAD needed)."""
from __future__ import annotations

import math
from typing import Tuple

#: Height of the horizontal work plane for task areas.
WORKPLANE_HEIGHT_M = 0.80
#: Band along the walls left out of a room's calculation grid.
WALL_BAND_M = 0.50
#: Largest grid spacing the rule allows.
MAX_SPACING_M = 10.0


def grid_spacing_m(longer_side_m: float) -> float:
    """Maximum grid spacing p = 0.2 * 5^log10(d) m for an area whose longer side is d metres
    (EN 12464-1), capped at 10 m. d = 5 m gives p = 0.61 m, d = 10 m gives 1.0 m."""
    if longer_side_m <= 0.0:
        raise ValueError(f"grid area side must be > 0 m (got {longer_side_m})")
    return min(0.2 * 5.0 ** math.log10(longer_side_m), MAX_SPACING_M)


def grid_cells(length_u_m: float, length_v_m: float, spacing_m: float = 0.0) -> Tuple[int, int, float]:
    """Number of grid cells along u and v, and the spacing used.

    ``spacing_m`` <= 0 selects the EN 12464-1 spacing from the longer side; the same spacing
    applies to both sides, n = ceil(side / p) (at least 1).
    """
    if length_u_m <= 0.0 or length_v_m <= 0.0:
        raise ValueError(f"grid area must have positive sides (got {length_u_m} x {length_v_m} m)")
    p = spacing_m if spacing_m > 0.0 else grid_spacing_m(max(length_u_m, length_v_m))
    # A tiny tolerance keeps 4.0 m / 0.5 m at 8 cells despite floating-point noise.
    nu = max(1, math.ceil(length_u_m / p - 1e-9))
    nv = max(1, math.ceil(length_v_m / p - 1e-9))
    return nu, nv, p
