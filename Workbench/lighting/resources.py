# SPDX-License-Identifier: LGPL-2.1-or-later
"""Where the shipped data lives (``Resources/`` of the source tree): photometric samples, the
EN 12464-1 requirements table. The workbench is installed as a symlink of ``Workbench/`` (the
data is beside it in the checkout) or as a copy (scripts/install-workbench.sh --copy puts the
data into ``Mod/Lighting/Resources``)."""
from __future__ import annotations

import os
from typing import List, Optional


def candidates(*parts: str) -> List[str]:
    """Possible places of ``Resources/<parts>``, most specific first."""
    found = []
    for here in (os.path.abspath(__file__), os.path.realpath(__file__)):
        workbench = os.path.dirname(os.path.dirname(here))  # .../Workbench or Mod/Lighting
        found.append(os.path.join(workbench, "Resources", *parts))
        found.append(os.path.join(os.path.dirname(workbench), "Resources", *parts))
    return list(dict.fromkeys(found))


def find(*parts: str) -> Optional[str]:
    """The first existing ``Resources/<parts>``, or None."""
    for path in candidates(*parts):
        if os.path.exists(path):
            return path
    return None
