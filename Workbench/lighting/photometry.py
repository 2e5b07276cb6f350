# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facts of IES LM-63 / EULUMDAT files, read by the solver's own parsers
(``lightsolver.photometry_summary``, docs/photometry.md): the workbench never parses these
files itself, so it cannot disagree with the solver about them. Without the native module
there are no facts, and the callers get a clear error saying why."""
from __future__ import annotations

from typing import Any, Dict, Optional

from lighting.messages import SolverUnavailableError

#: Extensions offered in file dialogs (the solver also recognises other names by content).
EXTENSIONS = (".ies", ".ldt")


def summary(path: str) -> Dict[str, Any]:
    """``lightsolver.photometry_summary(path)``: lamp_lumens_lm (None for absolute
    photometry), integrated_lumens_lm, peak_cd, beam_angle_deg / field_angle_deg (C0 and C90
    planes), warnings, text, ...

    Raises ValueError for a file the parser rejects (the message names the file and line) or
    when the solver module cannot be imported (nothing else reads these files)."""
    from lighting.solver import run

    try:
        module = run.load_module()
    except SolverUnavailableError as exc:
        raise ValueError(f"{path}: photometric files are read by the solver's parser, and "
                         f"lightsolver cannot be imported ({exc})") from exc
    reader = getattr(module, "photometry_summary", None)
    if reader is None:
        raise ValueError(f"{path}: this lightsolver build predates photometry_summary(); "
                         "rebuild it to read photometric files")
    return dict(reader(str(path)))


def rated_lumens(path: str) -> Optional[float]:
    """Rated lamp lumens of an IES or LDT file (None: absolute photometry). Raises ValueError
    as :func:`summary` does."""
    lumens = summary(path)["lamp_lumens_lm"]
    return None if lumens is None else float(lumens)
