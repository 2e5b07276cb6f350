# SPDX-License-Identifier: LGPL-2.1-or-later
"""Initial (new-installation) values: the illuminance before the maintenance factor.

The scene's flux is the maintained flux (initial flux × MF; docs/scene-format.md). Illuminance
is linear in each luminaire's flux, so

* when every luminaire that emits light shares one MF, initial values are the maintained ones
  ÷ MF, their intervals too (E_min, E_max and the uniformities of a grid scale alike);
* when the MFs differ but every luminaire group (the results' ``groups``) has one MF, the
  initial values are the run rescaled by 1/MF_g per group (``lightsolver.rescale``: every
  estimate, interval and grid statistic recomputed from each group's tallies, exactly as the
  light scenes are; E_initial = Σ_g E_g / MF_g);
* otherwise no single division is right, and the page says why instead of guessing.

A luminaire without an MF counts at its flux as given (MF 1)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Sequence

import lightsolver_results
from lightsolver_results import LuminaireFlux, Stat

#: Statistics that have an initial value (the uniformities do not change with one factor and
#: are recomputed by the rescale otherwise, but the report prints initial illuminances only).
KEYS = ("em", "emin", "emax")

RescaleFn = Callable[[Dict[str, Any], Dict[str, float]], Dict[str, Any]]


@dataclass
class InitialValues:
    """Initial values per calculation area, or why there are none.

    ``stats`` maps an area's name to {"em"|"emin"|"emax": Stat}; empty with ``missing`` saying
    why (in the client's words) when MFs are given but no exact initial value can be had, and
    empty with ``missing`` "" when no luminaire has an MF other than 1."""

    common_mf: Optional[float] = None
    #: Each group's MF where they differ (the group's name as the client reads it).
    group_mfs: Dict[str, float] = field(default_factory=dict)
    stats: Dict[str, Dict[str, Stat]] = field(default_factory=dict)
    missing: str = ""

    @property
    def available(self) -> bool:
        return bool(self.stats)

    @property
    def mf_range(self) -> Optional[str]:
        """"0.70 … 0.80" of the groups' MFs (None with a common MF)."""
        if not self.group_mfs:
            return None
        values = sorted(self.group_mfs.values())
        return f"{values[0]:.2f} … {values[-1]:.2f}"


def luminaire_mfs(scene: Dict[str, Any]) -> Dict[str, float]:
    """Each luminaire's MF by name (1 where none is given or it does not apply: a photometric
    file at its own absolute flux), by the schedule's rule (``schedule.maintenance_factor``)."""
    from lightsolver_report.schedule import maintenance_factor

    meta = scene.get("metadata") if isinstance(scene.get("metadata"), dict) else {}
    per_lum = meta.get("luminaires") if isinstance(meta.get("luminaires"), dict) else {}
    out = {}
    for lum in scene.get("luminaires", []):
        if isinstance(lum, dict):
            name = str(lum.get("name", ""))
            out[name] = maintenance_factor(lum, per_lum.get(name)) or 1.0
    return out


def _scaled(stat: Optional[Stat], factor: float) -> Optional[Stat]:
    if stat is None or stat.value is None:
        return None
    low = None if stat.low is None else stat.low * factor
    high = None if stat.high is None else stat.high * factor
    return Stat(stat.value * factor, low, high)


def _stats_of(target: lightsolver_results.Target, factor: float = 1.0) -> Dict[str, Stat]:
    found = {"em": _scaled(target.em, factor)}
    if target.is_grid:
        found["emin"], found["emax"] = _scaled(target.emin, factor), _scaled(target.emax, factor)
    return {k: s for k, s in found.items() if s is not None}


def initial_values(scene: Dict[str, Any], doc: Dict[str, Any],
                   targets: Sequence[lightsolver_results.Target],
                   traced: Sequence[LuminaireFlux], rescale: Optional[RescaleFn],
                   group_labels: Optional[Dict[str, str]] = None) -> InitialValues:
    """The initial values of the results ``doc`` (read as ``targets``; ``traced`` its
    luminaires' flux) by the module's rules."""
    mfs = luminaire_mfs(scene)
    emitting = [lum.name for lum in traced if lum.emitted_flux_lm > 0]
    found = {mfs.get(name, 1.0) for name in emitting}
    out = InitialValues()
    if found <= {1.0}:
        return out  # no maintenance factor: maintained and initial are the same
    if len(found) == 1:
        out.common_mf = found.pop()
        out.stats = {t.name: _stats_of(t, 1.0 / out.common_mf) for t in targets
                     if not t.is_glare}
        return out
    return _per_group(out, scene, doc, emitting, mfs, rescale, group_labels or {})


def _per_group(out: InitialValues, scene: Dict[str, Any], doc: Dict[str, Any],
               emitting: List[str], mfs: Dict[str, float], rescale: Optional[RescaleFn],
               labels: Dict[str, str]) -> InitialValues:
    """Different MFs: the run rescaled by 1/MF per group, where each group has one MF."""
    lit = set(emitting)
    factors: Dict[str, float] = {}
    for group in doc.get("groups", []):
        if not isinstance(group, dict):
            continue
        name = str(group.get("name"))
        members = {mfs.get(str(n), 1.0) for n in group.get("luminaires", []) if str(n) in lit}
        if len(members) > 1:
            out.missing = (f"luminaires with different maintenance factors are switched together "
                           f"in {labels.get(name, name)}, so the calculation cannot separate "
                           "their light")
            return out
        if members:
            factors[name] = 1.0 / members.pop()
            out.group_mfs[labels.get(name, name)] = 1.0 / factors[name]
    has_parts = any(isinstance(t, dict) and "contributions" in t for t in doc.get("targets", []))
    if not factors or not has_parts:
        out.group_mfs = {}
        out.missing = ("the luminaires have different maintenance factors and the calculation "
                       "did not keep each group's share of the light")
        return out
    if rescale is None:
        out.group_mfs = {}
        out.missing = "the solver module that separates the groups' light is not available"
        return out
    try:
        new = rescale(doc, {g: f for g, f in factors.items() if f != 1.0})
    except (ValueError, RuntimeError) as exc:
        out.group_mfs = {}
        out.missing = f"the groups' light could not be separated ({exc})"
        return out
    read = lightsolver_results.read(new, scene, strict=False, check_schema=False)
    out.stats = {t.name: _stats_of(t) for t in read.targets if not t.is_glare}
    return out
