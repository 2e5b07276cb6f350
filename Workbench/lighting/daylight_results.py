# SPDX-License-Identifier: LGPL-2.1-or-later
"""Daylight-factor results as the workbench shows them (docs/scene-format.md, "Results"): a DF grid's
``daylight_factor`` object of the results document, its cells for the false colours, its
figures with their intervals for the results table, the EN 17037 verdicts in words, and the
colour scale in %. App code (no GUI): the 3D view (viewproviders/daylight_coloring.py) and the
results table (taskpanels/results_table.py) use it."""
from __future__ import annotations

from typing import Any, Dict, List, Optional, Tuple

from lighting.colormap import Scale, auto_scale

#: The DF verdict keys in the user's words (EN 17037's daylight factor method).
VERDICT_NAMES = {"df_target": ("DF over 50 % of the area", " %"),
                 "df_minimum": ("DF over 95 % of the area", " %")}
#: The figures of a DF result in table order: (label, value key, interval keys).
FIGURES = (("DF mean", "mean_percent", ("ci_low_percent", "ci_high_percent")),
           ("DF min", "min_percent", ("min_ci_low_percent", "min_ci_high_percent")),
           ("DF over 50 %", "p50_percent", ("p50_ci_low_percent", "p50_ci_high_percent")),
           ("DF over 95 %", "p95_percent", ("p95_ci_low_percent", "p95_ci_high_percent")))
LEGEND_TITLE = "Daylight factor [%]"


def of_target(document: Optional[Dict[str, Any]], target_name: str) -> Optional[Dict[str, Any]]:
    """The ``daylight_factor`` object of a target in a results document, or None."""
    for entry in (document or {}).get("targets", []):
        if entry.get("name") == target_name:
            found = entry.get("daylight_factor")
            return found if isinstance(found, dict) else None
    return None


def target_entry(document: Optional[Dict[str, Any]], target_name: str) -> Dict[str, Any]:
    """A target's whole entry in a results document ({} when absent)."""
    for entry in (document or {}).get("targets", []):
        if entry.get("name") == target_name:
            return entry
    return {}


def cells_percent(daylight: Optional[Dict[str, Any]]) -> List[float]:
    """The cells' DF in % (row by row, as the grid's lux cells)."""
    if not daylight:
        return []
    return [float(c.get("percent", 0.0)) for c in daylight.get("cells", [])]


def interval_text(low: Any, high: Any, digits: int = 2) -> str:
    """"low - high" or "-" when the results give no interval."""
    if low is None or high is None:
        return "-"
    return f"{float(low):.{digits}f} - {float(high):.{digits}f}"


def figure_lines(daylight: Dict[str, Any]) -> List[Tuple[str, str, str]]:
    """(figure, value, interval) of a DF result: mean, minimum, the DF reached over 50 % and
    95 % of the area, each with its interval."""
    lines = []
    for label, key, (low, high) in FIGURES:
        if key in daylight:
            lines.append((label, f"{float(daylight[key]):.2f} %",
                          interval_text(daylight.get(low), daylight.get(high))))
    outside = daylight.get("outside_illuminance_lx")
    if outside is not None:
        lines.append(("Outside (sky)", f"{float(outside):.0f} lx", "-"))
    return lines


def verdict_word(verdict: Optional[str]) -> str:
    """"pass", "FAIL", "undecided" (or "" for none)."""
    if verdict is None:
        return ""
    return {"pass": "pass", "fail": "FAIL"}.get(verdict, "undecided")


def requirement_lines(entry: Dict[str, Any]) -> List[Tuple[str, str]]:
    """("DF over 50 % of the area >= 3.14 %", "pass") per DF verdict of a target's entry, with
    the EN 17037 level they come from first when given."""
    out = []
    wanted = entry.get("requirements", {}) or {}
    if wanted.get("en17037"):
        median = float(wanted.get("median_diffuse_lx", 0))
        out.append((f"EN 17037 {wanted['en17037']} at {median:.0f} lx", ""))
    for key, verdict in (entry.get("verdicts", {}) or {}).items():
        if key not in VERDICT_NAMES:
            continue
        name, unit = VERDICT_NAMES[key]
        relation = "<=" if verdict.get("relation") == "<=" else ">="
        out.append((f"{name} {relation} {float(verdict.get('required', 0.0)):.2f}{unit}",
                    verdict_word(verdict.get("verdict"))))
    return out


def table_values(daylight: Dict[str, Any]) -> Tuple[str, str]:
    """(the essential column's value, its interval) of a DF grid: its mean DF."""
    return (f"DF {float(daylight.get('mean_percent', 0.0)):.2f} %",
            interval_text(daylight.get("ci_low_percent"), daylight.get("ci_high_percent")))


def scale(document: Optional[Dict[str, Any]], target_names: List[str],
          colour_map: str = "Rainbow") -> Optional[Scale]:
    """The DF colour scale of an analysis: 0 to a round maximum over its DF grids' cells and
    means, in %; None without DF results."""
    values: List[float] = []
    for name in target_names:
        daylight = of_target(document, name)
        if daylight is not None:
            values.append(float(daylight.get("mean_percent", 0.0)))
            values.extend(cells_percent(daylight))
    if not values:
        return None
    low, high = auto_scale(values)
    return Scale(low, high, colour_map)


def overall_verdict(document: Optional[Dict[str, Any]], target_names: List[str]) -> str:
    """The DF grids' verdict together: FAIL if any fails, undecided if any is undecided,
    pass if all pass, "" when none is judged."""
    words = []
    for name in target_names:
        entry = target_entry(document, name)
        if "daylight_factor" in entry and entry.get("verdict"):
            words.append(verdict_word(entry["verdict"]))
    if not words:
        return ""
    for word in ("FAIL", "undecided"):
        if word in words:
            return word
    return "pass"
