# SPDX-License-Identifier: LGPL-2.1-or-later
"""Daylight-factor grids: a grid target's ``Quantity`` and its daylight requirements
(docs/scene-format.md, "Targets", docs/scene-format.md "Targets"), kept apart from
objects/target.py's illuminance requirements.

A grid with ``Quantity`` "Daylight factor" exports ``"quantity": "daylight_factor"`` and only
daylight requirements: EN 17037's level (minimum / medium / high) with the site's median
external diffuse illuminance, and/or explicit D_T / D_TM in percent (0 = not set; an explicit
value replaces the one the level derives). Illuminance requirements (RequiredLux,
RequiredUniformity, the Activity's task) are not exported for it: the solver refuses them on a
daylight-factor grid."""
from __future__ import annotations

from typing import Any, Dict

from lighting.objects.base import Prop

QUANTITIES = ("Illuminance", "Daylight factor")
DAYLIGHT_LEVELS = ("None", "Minimum", "Medium", "High")
#: EN 17037:2018 Table A.1 (vertical and inclined openings): (E_T, E_TM) in lx per level.
EN17037_TARGET_LUX = {"Minimum": (300.0, 100.0), "Medium": (500.0, 300.0),
                      "High": (750.0, 500.0)}
SOURCE = "EN 17037:2018, daylight factor method"

DAYLIGHT_PROPERTIES: Dict[str, Prop] = {
    "Quantity": Prop("App::PropertyEnumeration", "Grid",
                     "Grid: what it reports: Illuminance (lx) or Daylight factor (% of the "
                     "unobstructed sky's horizontal illuminance; needs one Sky)",
                     "Illuminance", items=QUANTITIES),
    "DaylightLevel": Prop("App::PropertyEnumeration", "Daylight",
                          "EN 17037 daylight provision level judged by the daylight factor "
                          "method (needs MedianDiffuseLux): None, Minimum (300/100 lx), Medium "
                          "(500/300 lx), High (750/500 lx)", "None", items=DAYLIGHT_LEVELS),
    "MedianDiffuseLux": Prop("App::PropertyFloat", "Daylight",
                             "EN 17037 median external diffuse illuminance E_v,d,med of the "
                             "site in lx (a weather file's: Chicago 15 900); 0 = not set", 0.0),
    "DaylightFactorTargetPercent": Prop("App::PropertyFloat", "Daylight",
                                        "D_T: daylight factor reached over 50 % of the grid, "
                                        "in %; 0 = from DaylightLevel (or none)", 0.0),
    "DaylightFactorMinimumPercent": Prop("App::PropertyFloat", "Daylight",
                                         "D_TM: daylight factor reached over 95 % of the grid, "
                                         "in %; 0 = from DaylightLevel (or none)", 0.0),
}


def is_daylight_factor(obj: Any) -> bool:
    """A grid target reporting daylight factors."""
    return (getattr(obj, "TargetType", "") == "Grid" and
            getattr(obj, "Quantity", "Illuminance") == "Daylight factor")


def derived_percent(obj: Any) -> Dict[str, float]:
    """D_T and D_TM the EN 17037 level gives at MedianDiffuseLux (empty without both)."""
    level, median = str(obj.DaylightLevel), float(obj.MedianDiffuseLux)
    if level not in EN17037_TARGET_LUX or median <= 0.0:
        return {}
    target_lx, minimum_lx = EN17037_TARGET_LUX[level]
    return {"df_target_percent": target_lx / median * 100.0,
            "df_minimum_percent": minimum_lx / median * 100.0}


def requirements_entry(obj: Any) -> Dict[str, Any]:
    """The scene-entry keys of a daylight-factor grid: ``quantity`` and its ``requirements``
    (``en17037`` + ``median_diffuse_lx``, explicit ``df_*_percent``); values are passed as
    they are (the solver names a bad one)."""
    entry: Dict[str, Any] = {"quantity": "daylight_factor"}
    wanted: Dict[str, Any] = {}
    if str(obj.DaylightLevel) in EN17037_TARGET_LUX:
        wanted["en17037"] = str(obj.DaylightLevel).lower()
        wanted["median_diffuse_lx"] = float(obj.MedianDiffuseLux)
    if float(obj.DaylightFactorTargetPercent) > 0.0:
        wanted["df_target_percent"] = float(obj.DaylightFactorTargetPercent)
    if float(obj.DaylightFactorMinimumPercent) > 0.0:
        wanted["df_minimum_percent"] = float(obj.DaylightFactorMinimumPercent)
    if wanted:
        entry["requirements"] = wanted
    return entry


def has_requirements(obj: Any) -> bool:
    """Whether a daylight-factor grid has anything to judge."""
    return "requirements" in requirements_entry(obj)
