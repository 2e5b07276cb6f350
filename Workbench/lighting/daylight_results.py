# SPDX-License-Identifier: LGPL-2.1-or-later
"""Daylight-factor results as the workbench shows them (docs/scene-format.md, "Results"): a DF grid's
daylight factor as the results reader gives it (``lightsolver_results.DaylightFactorView`` on
the reader's ``Target``; never the document's keys by hand), its cells for the false colours, its
figures with their intervals for the results table, the EN 17037 verdicts in words, and the
colour scale in %. App code (no GUI): the 3D view (viewproviders/daylight_coloring.py) and the
results table (taskpanels/results_table.py) use it."""
from __future__ import annotations

from typing import Any, Dict, List, Optional, Tuple

from lighting.colormap import Scale, auto_scale

#: The DF verdict keys in the user's words (EN 17037's daylight factor method).
VERDICT_NAMES = {"df_target": ("DF over 50 % of the area", " %"),
                 "df_minimum": ("DF over 95 % of the area", " %")}
#: The figures of a DF result in table order: (label, the view's statistic).
FIGURES = (("DF mean", "mean"), ("DF min", "min"), ("DF over 50 %", "p50"),
           ("DF over 95 %", "p95"))
LEGEND_TITLE = "Daylight factor [%]"


def _typed(document: Optional[Dict[str, Any]]) -> Optional[Any]:
    """A results document as the reader's typed results (None for none)."""
    from lighting.objects import results as results_obj

    return results_obj.read(document)


def target_of(document: Optional[Dict[str, Any]], target_name: str) -> Optional[Any]:
    """The reader's ``Target`` of a DF grid in a results document, or None (no such target,
    or not a daylight-factor grid)."""
    typed = _typed(document)
    for target in (typed.targets if typed is not None else []):
        if target.name == target_name and target.daylight_factor is not None:
            return target
    return None


def of_target(document: Optional[Dict[str, Any]], target_name: str) -> Optional[Any]:
    """A DF grid's ``DaylightFactorView`` in a results document, or None."""
    target = target_of(document, target_name)
    return target.daylight_factor if target is not None else None


def cells_percent(daylight: Optional[Any]) -> List[float]:
    """The cells' DF in % (row by row, as the grid's lux cells; 0 where a cell has none)."""
    if daylight is None:
        return []
    return [float(v) if v is not None else 0.0 for v in daylight.cells]


def interval_text(low: Any, high: Any, digits: int = 2) -> str:
    """"low - high" or "-" when the results give no interval."""
    if low is None or high is None:
        return "-"
    return f"{float(low):.{digits}f} - {float(high):.{digits}f}"


def figure_lines(daylight: Any) -> List[Tuple[str, str, str]]:
    """(figure, value, interval) of a DF result: mean, minimum, the DF reached over 50 % and
    95 % of the area, each with its interval, then the sky's outside illuminance."""
    lines = []
    for label, name in FIGURES:
        stat = getattr(daylight, name)
        if stat is not None and stat.value is not None:
            lines.append((label, f"{float(stat.value):.2f} %",
                          interval_text(stat.low, stat.high)))
    if daylight.outside_illuminance_lx is not None:
        lines.append(("Outside (sky)", f"{float(daylight.outside_illuminance_lx):.0f} lx", "-"))
    return lines


def verdict_word(verdict: Optional[str]) -> str:
    """"pass", "FAIL", "undecided" (or "" for none)."""
    if verdict is None:
        return ""
    return {"pass": "pass", "fail": "FAIL"}.get(verdict, "undecided")


def requirement_lines(target: Any) -> List[Tuple[str, str]]:
    """("DF over 50 % of the area >= 3.14 %", "pass") per DF verdict of a DF grid (the
    reader's ``Target``, or the workbench's ``TargetResult``: ``requirements``, ``verdicts``
    and ``verdict_of``), with the EN 17037 level they come from first when given."""
    out = []
    wanted = dict(getattr(target, "daylight_requirements", None)
                  or getattr(target, "requirements", None) or {})
    if wanted.get("en17037"):
        median = float(wanted.get("median_diffuse_lx", 0))
        out.append((f"EN 17037 {wanted['en17037']} at {median:.0f} lx", ""))
    verdict_of = target.verdict_of
    for key in VERDICT_NAMES:
        judged = target.verdicts.get(key)
        if judged is None:
            continue
        name, unit = VERDICT_NAMES[key]
        relation = "<=" if judged.get("relation") == "<=" else ">="
        word = verdict_of(key) if callable(verdict_of) else verdict_of.get(key)
        out.append((f"{name} {relation} {float(judged.get('required', 0.0)):.2f}{unit}",
                    verdict_word(word)))
    return out


def table_values(daylight: Any) -> Tuple[str, str]:
    """(the essential column's value, its interval) of a DF grid: its mean DF."""
    mean = daylight.mean
    return (f"DF {float(mean.value or 0.0):.2f} %", interval_text(mean.low, mean.high))


def scale(document: Optional[Dict[str, Any]], target_names: List[str],
          colour_map: str = "Rainbow") -> Optional[Scale]:
    """The DF colour scale of an analysis: 0 to a round maximum over its DF grids' cells and
    means, in %; None without DF results."""
    values: List[float] = []
    for name in target_names:
        daylight = of_target(document, name)
        if daylight is not None:
            values.append(float(daylight.mean.value or 0.0))
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
        target = target_of(document, name)
        if target is not None and target.verdict:
            words.append(verdict_word(target.verdict))
    if not words:
        return ""
    for word in ("FAIL", "undecided"):
        if word in words:
            return word
    return "pass"
