# SPDX-License-Identifier: LGPL-2.1-or-later
"""Deciding the undecided requirements: the photon budget of a Decide run, what it costs, and
whether a run continues by itself to decide them.

The solver forecasts, per undecided requirement, the photons of a whole run that would put the
interval's end just on the bound (``to_decide``: photons and tracing seconds at the run's rate,
docs/statistics.md "What deciding would cost"). A run of exactly that many decides only about
half the time (the estimate moves as much as the interval shrinks), so a Decide run's budget
is :data:`MARGIN` times the largest forecast, at least twice what was traced; a decide run
stops at its first look where every requirement is decided, so the margin costs photons only
when they are needed.

**Automatic continuation.** A decide run (Decide on, no accuracy goal) that spent its budget
with requirements still undecided goes on by itself with that budget when tracing it would
take at most :func:`limit_seconds` (the preference ``DecideLimitSeconds``, default
:data:`DEFAULT_LIMIT_S`; 0 turns it off). Beyond the limit it stops, and the panel says what
deciding needs and why the run did not do it. This is App code: the headless
``lighting.analyze`` continues the same way."""
from __future__ import annotations

import math
from typing import List, NamedTuple, Optional, Tuple

from lighting.solver import results as results_mod

#: Budget of a Decide run over the largest forecast (see the module doc).
MARGIN = 4
#: The preference (group BaseApp/Preferences/Mod/Lighting) holding the automatic limit.
LIMIT_PARAM = "DecideLimitSeconds"
PARAM_GROUP = "User parameter:BaseApp/Preferences/Mod/Lighting"
#: Tracing seconds a run may add by itself to decide its requirements.
DEFAULT_LIMIT_S = 30.0


class Plan(NamedTuple):
    """What deciding every undecided requirement of a result takes."""

    #: (target label, requirement key) of each undecided requirement.
    undecided: List[Tuple[str, str]]
    #: The largest forecast (photons of a whole run); 0 when none can be forecast.
    forecast: int
    #: The Decide run's photon budget (MARGIN x the forecast, >= 2 x traced); 0: no run can.
    budget: int
    #: Tracing seconds of the whole budget at the run's rate (an upper bound: the run stops
    #: when everything is decided); None when the results give no rate.
    seconds: Optional[float]
    #: Requirements whose value sits on the bound: no run decides them.
    undecidable: List[Tuple[str, str]]

    def within(self, limit_s: float) -> bool:
        """Whether a run may continue by itself: a budget whose time is known and at most
        ``limit_s`` (> 0)."""
        return (self.budget > 0 and limit_s > 0.0 and self.seconds is not None
                and self.seconds <= limit_s)


def limit_seconds() -> float:
    """The automatic continuation limit in tracing seconds (0: off); the preference
    ``DecideLimitSeconds``, else :data:`DEFAULT_LIMIT_S`."""
    try:
        import FreeCAD

        value = FreeCAD.ParamGet(PARAM_GROUP).GetFloat(LIMIT_PARAM, DEFAULT_LIMIT_S)
    except Exception:  # noqa: BLE001 - outside FreeCAD
        return DEFAULT_LIMIT_S
    return max(float(value), 0.0) if math.isfinite(value) else DEFAULT_LIMIT_S


def budget_for(forecast: float, traced: float) -> int:
    """A Decide run's budget: MARGIN x ``forecast``, at least twice ``traced``, rounded up to a
    thousand."""
    wanted = max(MARGIN * float(forecast), 2.0 * float(traced))
    return int(math.ceil(wanted / 1000.0) * 1000)


def plan(result: Optional[results_mod.AnalysisResult]) -> Optional[Plan]:
    """What deciding ``result``'s undecided requirements takes; None when none is undecided
    (point estimates are never undecided)."""
    if result is None:
        return None
    undecided, undecidable, forecast, seconds_per_photon = [], [], 0, None
    for t in result.targets:
        if t.estimated:
            continue
        for key in t.undecided:
            undecided.append((t.label, key))
            photons, seconds = t.to_decide.get(key, (None, None))
            if photons is None:
                undecidable.append((t.label, key))
                continue
            if photons >= forecast:
                forecast = int(photons)
                if seconds is not None and photons > 0:
                    seconds_per_photon = float(seconds) / float(photons)
    if not undecided:
        return None
    if forecast <= 0 or undecidable:
        return Plan(undecided, forecast, 0, None, undecidable)
    if seconds_per_photon is None and result.photons > 0 and result.seconds > 0:
        seconds_per_photon = result.seconds / result.photons
    budget = budget_for(forecast, result.photons)
    seconds = budget * seconds_per_photon if seconds_per_photon is not None else None
    return Plan(undecided, forecast, budget, seconds, undecidable)


def photons_text(photons: float) -> str:
    """"4.1 M", "253 821" (narrow no-break spaces): photons as a person reads them."""
    if photons >= 1.0e6:
        return f"{photons / 1.0e6:.1f}\u202fM"
    return f"{photons:,.0f}".replace(",", "\u202f")
