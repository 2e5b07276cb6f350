# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of observers (eyes for glare): a blue eye, its line of sight and the
outline of the UGR field."""
from __future__ import annotations

from typing import Any

from lighting.viewproviders.base import ViewProviderBase, set_if_exists


class ViewProviderObserver(ViewProviderBase):
    """Observer symbol in blue."""

    ICON = "Lighting_Observer"

    def __init__(self, vobj: Any) -> None:
        super().__init__(vobj)
        set_if_exists(vobj, "ShapeColor", (0.2, 0.45, 0.95))
        set_if_exists(vobj, "LineColor", (0.1, 0.3, 0.9))
        set_if_exists(vobj, "LineWidth", 2.0)
