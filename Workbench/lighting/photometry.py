# SPDX-License-Identifier: LGPL-2.1-or-later
"""The few facts the workbench needs from IES LM-63 / EULUMDAT files (the solver reads the
distribution itself, see docs/photometry.md): the rated lamp lumens, so the maintenance
factor can be applied to a luminaire that uses the file's own flux."""
from __future__ import annotations

import os
import re
from typing import List, Optional

EXTENSIONS = (".ies", ".ldt")


def _numbers(text: str) -> List[float]:
    return [float(t) for t in re.split(r"[\s,]+", text.strip()) if t]


def ies_rated_lumens(path: str) -> Optional[float]:
    """Lamps x lumens per lamp of an IES file; None for absolute photometry (-1)."""
    with open(path, encoding="latin-1") as stream:
        lines = stream.read().splitlines()
    for index, line in enumerate(lines):
        if line.strip().upper().startswith("TILT="):
            rest = " ".join(lines[index + 1:])
            tokens = _numbers(rest)
            if line.strip().upper() == "TILT=INCLUDE":
                count = int(tokens[1])
                tokens = tokens[2 + 2 * count:]
            lamps, lumens = tokens[0], tokens[1]
            return None if lumens < 0 else lamps * lumens
    raise ValueError(f"{path}: no TILT= line (not an IES LM-63 file?)")


def ldt_rated_lumens(path: str) -> Optional[float]:
    """Total flux of the lamp sets of a EULUMDAT file; None for absolute photometry."""
    with open(path, encoding="latin-1") as stream:
        lines = [line.strip() for line in stream.read().splitlines()]
    sets = int(float(lines[25].replace(",", ".")))
    counts = [float(lines[26 + i].replace(",", ".")) for i in range(sets)]
    fluxes = [float(lines[26 + 2 * sets + i].replace(",", ".")) for i in range(sets)]
    if any(c < 0 for c in counts):
        return None
    return sum(fluxes)


def rated_lumens(path: str) -> Optional[float]:
    """Rated lamp lumens of an IES or LDT file (None: absolute photometry).

    Raises ValueError (unknown extension, unreadable header) or OSError."""
    extension = os.path.splitext(path)[1].lower()
    try:
        if extension == ".ies":
            return ies_rated_lumens(path)
        if extension == ".ldt":
            return ldt_rated_lumens(path)
    except (IndexError, ValueError) as exc:
        raise ValueError(f"{path}: cannot read the lamp lumens ({exc})") from exc
    raise ValueError(f"{path}: photometric files must be .ies or .ldt")
