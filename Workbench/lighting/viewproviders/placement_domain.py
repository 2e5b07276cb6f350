# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of placement domains: the candidate positions as points."""
from __future__ import annotations

from typing import Any

from lighting.viewproviders.base import ViewProviderBase, set_if_exists


class ViewProviderPlacementDomain(ViewProviderBase):
    """Candidate luminaire positions drawn as orange points."""

    ICON = "Lighting_PlacementDomain"

    def __init__(self, vobj: Any) -> None:
        super().__init__(vobj)
        set_if_exists(vobj, "PointColor", (1.0, 0.55, 0.0))
        set_if_exists(vobj, "PointSize", 6.0)
