# SPDX-License-Identifier: LGPL-2.1-or-later
"""The results layout itself: its format tag, the schema and its check, and the plain JSON data
of a document (``lightsolver.solve()``'s dict without the numpy arrays it adds). The first step
of :func:`lightsolver_results.read`; the migration and the view build on it."""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, Dict, List, Optional

FORMAT = "lightsolver.results/1"
#: An optimizer's output (docs/schemas/optimization.schema.json): configurations, not results.
OPTIMIZATION_FORMAT = "lightsolver.optimization/1"
#: Grid-cell numpy arrays that ``lightsolver.solve()`` adds beside the results layout.
CELL_ARRAYS = ("cells_lux", "cells_ci_low_lux", "cells_ci_high_lux", "cells_hits")
#: Target types whose result is a UGR (an observer grid's is its maximum over its points).
GLARE_KINDS = ("observer", "observer_grid")
#: The target types :func:`lightsolver_results.read` knows the results of (the solver's target
#: type rows); of another type only the illuminance is read, and the notes say so.
READ_TYPES = ("surface", "grid") + GLARE_KINDS


class ResultsError(ValueError):
    """The document is no results document this reader understands; the message says where."""


def finite(value: Any) -> Optional[float]:
    """A finite number, or None (JSON null, absent, not a number)."""
    if isinstance(value, bool) or value is None:
        return None
    try:
        number = float(value)
    except (TypeError, ValueError):
        return None
    return number if math.isfinite(number) else None


def plain(raw: Dict[str, Any]) -> Dict[str, Any]:
    """The results as plain JSON data: ``lightsolver.solve()``'s dict without the numpy cell
    arrays it adds beside the layout (the CLI's file is already plain)."""
    out = {key: value for key, value in raw.items() if key != "targets"}
    out["targets"] = [{k: v for k, v in t.items() if k not in CELL_ARRAYS}
                      if isinstance(t, dict) else t for t in raw.get("targets") or []]
    return out


def _schema_path() -> Optional[Path]:
    here = Path(__file__).resolve().parent
    for path in (here / "results.schema.json",  # copied beside it by CMake
                 here.parents[2] / "docs" / "schemas" / "results.schema.json"):  # source tree
        if path.is_file():
            return path
    return None


_SCHEMA: Optional[Dict[str, Any]] = None


def schema() -> Optional[Dict[str, Any]]:
    """docs/schemas/results.schema.json, or None where neither copy is found."""
    global _SCHEMA
    if _SCHEMA is None:
        path = _schema_path()
        if path is not None:
            _SCHEMA = json.loads(path.read_text(encoding="utf-8"))
    return _SCHEMA


def check(doc: Dict[str, Any]) -> List[str]:
    """What in ``doc`` breaks the results schema ("path: message" each; empty: none). Without
    ``jsonschema`` or the schema file, only the format and the targets list are checked."""
    if not isinstance(doc, dict):
        return ["the results are not a JSON object"]
    if doc.get("format") != FORMAT:
        return [f"format: expected {FORMAT!r}, got {doc.get('format')!r}"]
    if not isinstance(doc.get("targets"), list):
        return ["targets: missing or not a list"]
    found = schema()
    try:
        import jsonschema
    except ImportError:
        return []
    if found is None:
        return []
    validator = jsonschema.Draft202012Validator(found)
    return [f"{'/'.join(map(str, e.absolute_path)) or '(top)'}: {e.message}"
            for e in sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path))]
