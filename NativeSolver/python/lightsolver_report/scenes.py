# SPDX-License-Identifier: LGPL-2.1-or-later
"""Light scenes (DIALux's light scenes): a dimming level per luminaire group, each scene's
results rescaled from the one run (``lightsolver.rescale``: estimates, intervals, statistics,
UGR and verdicts recomputed from the per-group tallies, no tracing; docs/statistics.md,
"Groups").

Where the scenes come from: ``light_scenes`` given to the report (the workbench's light
scenes), else the scene's ``metadata.light_scenes`` (docs/scene-format.md). Rescaling is
relative to the document it is given, so results that are themselves a light scene (the
workbench passes the scene it shows; their ``rescaled`` records each group's factor) are
rescaled by level / factor; a group off in them cannot be lit again, and the page says so."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Sequence

from lightsolver_report.wording import group_levels

RescaleFn = Callable[[Dict[str, Any], Dict[str, float]], Dict[str, Any]]


@dataclass
class LightScene:
    """A light scene: its name, levels per group, and (once rescaled) its results or why
    they are missing."""

    name: str
    levels: Dict[str, float]
    results: Optional[Dict[str, Any]] = None
    missing: str = ""  # why the results are not shown
    #: Filled by the model: the scene's calculation areas (model.Area) and verdict.
    areas: List[Any] = field(default_factory=list)
    verdict: Optional[str] = None
    #: The groups' names for the client (a layout's group is named after the layout).
    labels: Dict[str, str] = field(default_factory=dict)

    @property
    def description(self) -> str:
        return group_levels({self.labels.get(g, g): v for g, v in self.levels.items()})


def read_light_scenes(given: Any, metadata: Dict[str, Any],
                      labels: Optional[Dict[str, str]] = None) -> List[LightScene]:
    """The light scenes to report: ``given`` ({name: {group: level}} or a list of {name,
    levels}), else ``metadata.light_scenes``; levels that are not finite numbers >= 0 leave
    the scene out with a note in ``missing``."""
    source = given if given is not None else metadata.get("light_scenes")
    if isinstance(source, dict):
        source = [{"name": k, "levels": v} for k, v in source.items()]
    scenes = []
    for entry in source if isinstance(source, list) else []:
        if not isinstance(entry, dict):
            continue
        raw = entry.get("levels") if isinstance(entry.get("levels"), dict) else {}
        scene = LightScene(str(entry.get("name", "")), {}, labels=dict(labels or {}))
        for group, level in raw.items():
            if isinstance(level, bool) or not isinstance(level, (int, float)) \
                    or not math.isfinite(level) or level < 0:
                scene.missing = f"the level of {group} is not a number ≥ 0 ({level!r})"
                break
            scene.levels[str(group)] = float(level)
        scenes.append(scene)
    return scenes


def rescale_factors(results: Dict[str, Any], levels: Dict[str, float]) -> Dict[str, float]:
    """Factors that turn ``results`` (perhaps already rescaled) into the scene ``levels``
    (groups not named at 1). ValueError naming a group that is off in ``results`` but lit in
    the scene (its contribution is gone)."""
    current = results.get("rescaled") if isinstance(results.get("rescaled"), dict) else {}
    groups = [str(g.get("name")) for g in results.get("groups", []) if isinstance(g, dict)]
    factors = {}
    for group in groups:
        now = float(current.get(group, 1.0))
        wanted = float(levels.get(group, 1.0))
        if now == wanted:
            continue
        if now == 0.0:
            raise ValueError(f"{group} is off in the results this report was given")
        factors[group] = wanted / now
    return factors


def fill(scenes: Sequence[LightScene], results: Dict[str, Any],
         rescale: Optional[RescaleFn]) -> None:
    """Rescale ``results`` to each scene (in place: ``results`` or ``missing``)."""
    has_parts = bool(results.get("groups")) and any(
        isinstance(t, dict) and "contributions" in t for t in results.get("targets", []))
    known = {str(g.get("name")) for g in results.get("groups", []) if isinstance(g, dict)}
    for scene in scenes:
        if scene.missing:
            continue
        unknown = sorted(set(scene.levels) - known)
        if not has_parts:
            scene.missing = ("the calculation did not keep each group's part (trace with "
                             "contributions to show light scenes)")
        elif unknown:
            scene.missing = f"no luminaire is in group {', '.join(unknown)}"
        elif rescale is None:
            scene.missing = "the solver module is not available to rescale the results"
        else:
            try:
                factors = rescale_factors(results, scene.levels)
                scene.results = rescale(results, factors) if factors else results
            except (ValueError, RuntimeError) as exc:
                scene.missing = str(exc)


def shown_scene(results: Dict[str, Any], scenes: Sequence[LightScene],
                labels: Optional[Dict[str, str]] = None) -> Optional[str]:
    """What rescaled ``results`` show: "light scene Evening (Window row 50 %)" when their
    factors are a scene's levels, else the levels; None for results as traced."""
    current = results.get("rescaled")
    if not isinstance(current, dict) or all(float(v) == 1.0 for v in current.values()):
        return None
    levels = {str(k): float(v) for k, v in current.items()}
    named = group_levels({(labels or {}).get(g, g): v for g, v in levels.items()})
    for scene in scenes:
        if all(scene.levels.get(g, 1.0) == v for g, v in levels.items()):
            return f"light scene {scene.name} ({named})"
    return f"dimmed groups ({named})"


def as_traced(results: Dict[str, Any], rescale: Optional[RescaleFn]) -> Optional[Dict[str, Any]]:
    """The results with every group at 100 % (``results`` themselves when not rescaled); None
    when that cannot be had (a group off, no solver module)."""
    current = results.get("rescaled")
    if not isinstance(current, dict) or all(float(v) == 1.0 for v in current.values()):
        return results
    if rescale is None:
        return None
    try:
        return rescale(results, rescale_factors(results, {}))
    except (ValueError, RuntimeError):
        return None


def solver_rescale() -> Optional[RescaleFn]:
    """``lightsolver.rescale`` when the module is importable."""
    try:
        import lightsolver

        return lightsolver.rescale
    except ImportError:
        return None
