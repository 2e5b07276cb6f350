# SPDX-License-Identifier: LGPL-2.1-or-later
"""The one migration step: results written by older solvers brought to the current layout.
Every legacy fallback of the Python readers lives here, and each one applied is said in the
notes :func:`migrate` returns:

* grids without ``min_lux``/``max_lux``/``uniformity`` (the oldest solvers): from the cells;
* no ``luminaires`` (before the solver recorded the traced flux): derived from the scene by the
  caller's ``scene_flux`` (TILT not applied);
* no ``warnings``/``groups``: empty lists;
* targets without the solver's verdicts (results of solvers that did not judge requirements, or
  requirements set after the run) for which the caller gives requirements: verdicts from the
  point estimates (:data:`ESTIMATED_NOTE`)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Mapping, Optional, Set, Tuple

from .layout import GLARE_KINDS, finite, plain

#: Said on every page that prints a flux derived from the scene instead of the traced one.
DERIVED_FLUX_NOTE = ("these results were written before the solver recorded each luminaire's "
                     "traced flux: the flux shown is derived from the scene, without a "
                     "photometric TILT table's factor")
#: Begins the note naming the targets whose verdicts :func:`migrate` estimated.
ESTIMATED_NOTE = ("verdicts estimated from the point estimates, not judged by the solver from "
                  "the intervals (these results carry none for them; never undecided): ")

#: Derives a luminaire's emitted flux (lm) from its scene entry, for results without
#: ``luminaires`` (the report passes one that reads the photometric files).
SceneFlux = Callable[[Dict[str, Any]], float]
#: Requirements by target name, with the scene file's keys (``em_lux``, ``u0``, ...).
Requirements = Mapping[str, Mapping[str, Any]]


def _ud(t: Dict[str, Any]) -> Optional[float]:
    low, high = finite(t.get("min_lux")), finite(t.get("max_lux"))
    found = finite(t.get("ud"))
    return found if found is not None else (low / high if low is not None and high else None)


@dataclass(frozen=True)
class _Rule:
    """How a requirement is judged: its verdict's name, the relation, the target types it
    applies to (docs/schemas/results.schema.json) and the estimate it is judged on."""

    verdict: str
    relation: str
    types: Tuple[str, ...]
    value: Callable[[Dict[str, Any]], Optional[float]]


#: The requirement keys of docs/scene-format.md, each with its rule.
RULES: Dict[str, _Rule] = {
    "em_lux": _Rule("em", ">=", ("surface", "grid"), lambda t: finite(t.get("mean_lux"))),
    "emin_lux": _Rule("emin", ">=", ("grid",), lambda t: finite(t.get("min_lux"))),
    "u0": _Rule("u0", ">=", ("grid",), lambda t: finite(t.get("uniformity"))),
    "ud": _Rule("ud", ">=", ("grid",), _ud),
    "ugr_max": _Rule("ugr", "<=", GLARE_KINDS, lambda t: finite(t.get("ugr"))),
}


def _migrate_grid(t: Dict[str, Any]) -> bool:
    """Grid statistics that the oldest solvers left out, from the cells: Emin, Emax and U0.
    True when something was added."""
    if t.get("type") != "grid":
        return False
    added = False
    lux = [finite(c.get("lux")) for c in t.get("cells") or [] if isinstance(c, dict)]
    lux = [v for v in lux if v is not None]
    if lux and "min_lux" not in t:
        t["min_lux"], added = min(lux), True
    if lux and "max_lux" not in t:
        t["max_lux"], added = max(lux), True
    mean = finite(t.get("mean_lux"))
    if "uniformity" not in t and "min_lux" in t:
        t["uniformity"], added = (t["min_lux"] / mean if mean else 0.0), True
    return added


def _estimate(t: Dict[str, Any], wanted: Optional[Mapping[str, Any]]) -> bool:
    """Verdicts from the point estimates for a target without the solver's: each requirement
    of ``wanted`` that applies to the target's type and has an estimate is judged by the
    solver's rule on an interval of zero width (the estimate itself: pass when it lies on the
    allowed side, the bound included, else fail), the overall verdict fail if any fails.
    True when the target got verdicts."""
    if "verdict" in t or not isinstance(wanted, Mapping):
        return False
    kind = str(t.get("type", "surface"))
    requirements: Dict[str, float] = {}
    verdicts: Dict[str, Dict[str, Any]] = {}
    for key, bound in wanted.items():
        rule, required = RULES.get(str(key)), finite(bound)
        value = rule.value(t) if rule is not None and kind in rule.types else None
        if rule is None or value is None or required is None or required <= 0.0:
            continue
        met = value >= required if rule.relation == ">=" else value <= required
        requirements[str(key)] = required
        verdicts[rule.verdict] = {"verdict": "pass" if met else "fail", "value": value,
                                  "ci_low": value, "ci_high": value, "required": required,
                                  "relation": rule.relation}
    if not verdicts:
        return False
    t["requirements"], t["verdicts"] = requirements, verdicts
    t["verdict"] = "fail" if any(v["verdict"] == "fail" for v in verdicts.values()) else "pass"
    return True


def _scene_luminaires(scene: Dict[str, Any], groups: List[Dict[str, Any]],
                      scene_flux: SceneFlux) -> List[Dict[str, Any]]:
    """``luminaires`` derived from the scene: each luminaire's flux by ``scene_flux`` (no TILT:
    tilt_factor 1), its group from the results' groups, else its scene ``group``, else itself."""
    group_of = {str(name): str(g.get("name")) for g in groups if isinstance(g, dict)
                for name in g.get("luminaires", [])}
    out = []
    for lum in scene.get("luminaires", []):
        if not isinstance(lum, dict):
            continue
        name = str(lum.get("name", ""))
        flux = float(scene_flux(lum))
        out.append({"name": name, "type": str(lum.get("type", "")),
                    "group": group_of.get(name, str(lum.get("group") or name)),
                    "flux_lm": flux, "tilt_factor": 1.0, "dimming": 1.0,
                    "emitted_flux_lm": flux})
    return out


def _migrate(doc: Dict[str, Any], scene: Optional[Dict[str, Any]] = None,
             scene_flux: Optional[SceneFlux] = None,
             requirements: Optional[Requirements] = None
             ) -> Tuple[Dict[str, Any], List[str], Set[str]]:
    """:func:`migrate`, and the names of the targets whose verdicts it estimated."""
    out = plain(doc)  # new top level and target dicts: the migration adds keys to these only
    notes: List[str] = []
    if not isinstance(out.get("targets"), list):
        out["targets"] = []
    for key in ("warnings", "groups"):
        if not isinstance(out.get(key), list):
            out[key] = []
    targets = [t for t in out["targets"] if isinstance(t, dict)]
    grids = [str(t.get("name", "")) for t in targets if _migrate_grid(t)]
    if grids:
        notes.append("grid statistics derived from the cells (results of an older solver): "
                     + ", ".join(grids))
    wanted = requirements or {}
    estimated = [str(t.get("name", "")) for t in targets
                 if _estimate(t, wanted.get(str(t.get("name", ""))))]
    if estimated:
        notes.append(ESTIMATED_NOTE + ", ".join(estimated))
    if "luminaires" not in out and scene is not None and scene_flux is not None:
        out["luminaires"] = _scene_luminaires(scene, out["groups"], scene_flux)
        notes.append(DERIVED_FLUX_NOTE)
    return out, notes, set(estimated)


def migrate(doc: Dict[str, Any], scene: Optional[Dict[str, Any]] = None,
            scene_flux: Optional[SceneFlux] = None,
            requirements: Optional[Requirements] = None) -> Tuple[Dict[str, Any], List[str]]:
    """A copy of ``doc`` in the current layout, and one note per fallback applied (empty for
    results of the current solver; the module docstring lists the fallbacks). ``scene`` and
    ``scene_flux`` derive the luminaires of results without them; ``requirements`` (by target
    name, scene-file keys) are judged on the point estimates of targets that carry no verdicts
    of the solver. The estimated verdicts keep the schema's layout (an interval of zero width:
    the estimate), so the migrated document still validates."""
    out, notes, _ = _migrate(doc, scene, scene_flux, requirements)
    return out, notes
