# SPDX-License-Identifier: LGPL-2.1-or-later
"""Light scene: a dimming level per control group (DIALux's light scenes).

Luminaires belong to control groups (``ControlGroup``; empty = a layout's members share the
layout's group, a single luminaire is its own). An analysis with ``Contributions`` on traces
each group's contribution separately (docs/statistics.md, "Groups"), so a light scene is shown
by rescaling that one trace (``lightsolver.rescale``): switching scenes or changing a level
costs no tracing, and the rescaled intervals, statistics and verdicts stay honest.

The analysis' ``ActiveLightScene`` says which scene the results object shows
(objects/results.py ``data``); none shows the results as traced (every group at 1)."""
from __future__ import annotations

import math
from typing import Any, Dict, List, Optional

from lighting.objects.base import BaseProxy, Prop, proxy_type
# The analysis whose group holds an object (a light scene here): one lookup for both.
from lighting.objects.results import analysis_of  # noqa: F401 - also used by callers

TYPE = "Lighting::LightScene"


class LightScene(BaseProxy):
    """Dimming levels of the control groups: level 1 = the flux the luminaires have, 0 = off."""

    TYPE = TYPE
    PROPERTIES = {
        "Groups": Prop("App::PropertyStringList", "Light scene",
                       "Control groups this scene sets (luminaires' ControlGroup); groups not "
                       "listed stay at level 1"),
        "Levels": Prop("App::PropertyFloatList", "Light scene",
                       "Dimming level of each group in Groups, same order: 1 = full flux, "
                       "0.5 = half, 0 = off"),
    }

    def onChanged(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        if prop in ("Groups", "Levels") and not getattr(obj.Document, "Restoring", False):
            show_changed(obj)


def levels(obj: Any) -> Dict[str, float]:
    """The scene's levels by group (ValueError naming the scene when they do not pair up or
    a level is negative or not finite)."""
    groups, values = list(obj.Groups), [float(v) for v in obj.Levels]
    if len(groups) != len(values):
        raise ValueError(f"Light scene '{obj.Label}': {len(groups)} groups but {len(values)} "
                         "levels (one level per group)")
    for group, value in zip(groups, values):
        if not math.isfinite(value) or value < 0.0:
            raise ValueError(f"Light scene '{obj.Label}': level of group '{group}' must be a "
                             f"number >= 0 (got {value:g})")
    return dict(zip(groups, values))


def describe(obj: Any, values: Dict[str, float]) -> str:
    """"Evening: Row 1 50 %, Row 2 off" (levels in per cent; groups at 1 not named)."""
    parts = [f"{group} {'off' if level == 0.0 else f'{level * 100:.4g} %'}"
             for group, level in values.items() if level != 1.0]
    return f"{obj.Label}: {', '.join(parts) if parts else 'all at 100 %'}"


def check(obj: Any, known_groups: List[str]) -> List[tuple]:
    """Problems of a light scene against the analysis' groups: list of (level, text)."""
    try:
        found = levels(obj)
    except ValueError as exc:
        return [("error", str(exc))]
    problems = []
    unknown = [g for g in found if g not in known_groups]
    if unknown:
        problems.append(("warning", f"Light scene '{obj.Label}': no luminaire is in group(s) "
                                    f"{', '.join(unknown)}"))
    # A luminaire added after the scene was made: its group is at 100 % in this scene, which
    # the user never chose; say so rather than let it pass silently.
    unset = [g for g in known_groups if g not in found]
    if unset:
        problems.append(("warning", f"Light scene '{obj.Label}' does not set group(s) "
                                    f"{', '.join(unset)} (made after the scene): they are at "
                                    "100 %; set their level in the analysis panel's light "
                                    "scenes"))
    return problems


def scenes(analysis: Any) -> List[Any]:
    """The light scenes in an analysis' group."""
    return [o for o in getattr(analysis, "Group", []) if proxy_type(o) == TYPE]


def active(analysis: Any) -> Optional[Any]:
    """The light scene an analysis shows, or None (results as traced)."""
    found = getattr(analysis, "ActiveLightScene", None)
    return found if found is not None and proxy_type(found) == TYPE else None


def show_changed(obj: Any) -> None:
    """A scene's levels changed: re-derive what its analysis' results object shows (the view
    providers repaint on that), when it is the scene shown."""
    analysis = analysis_of(obj)
    if analysis is not None and active(analysis) is obj:
        refresh(analysis)


def refresh(analysis: Any) -> None:
    """Re-derive the shown results of an analysis (after a scene switch or a level change)."""
    from lighting.objects import results as results_obj

    found = results_obj.of_analysis(analysis)
    if found is not None:
        results_obj.derive(found)


def make(analysis: Any, label: str = "Light scene",
         values: Optional[Dict[str, float]] = None) -> Any:
    """A light scene in ``analysis``' group: every control group of its luminaires at level
    1, then ``values``. It turns the analysis' Contributions on (the next run traces the
    groups separately) and becomes the scene shown."""
    from lighting.objects import analysis as analysis_mod

    doc = analysis.Document
    obj = doc.addObject("App::FeaturePython", "LightScene")
    LightScene(obj)
    obj.Label = label
    groups = analysis_mod.control_groups(analysis)
    wanted = dict.fromkeys(groups, 1.0)
    wanted.update(values or {})
    obj.Groups = list(wanted)
    obj.Levels = [float(v) for v in wanted.values()]
    analysis.addObject(obj)
    if not analysis.Contributions:
        analysis.Contributions = True
    analysis.ActiveLightScene = obj
    return obj
