# SPDX-License-Identifier: LGPL-2.1-or-later
"""Installed power and energy: the connected load per calculation area (W/m² and W/m² per
100 lx) and a LENI estimate (EN 15193-1, lighting energy numeric indicator, kWh/(m²·a)).

LENI uses the standard's energy of lighting in its simple form (EN 15193-1:2017, the
installed-power method; the same expression as EN 15193:2007's):

    W_L = P_n · F_C · F_O · (t_D · F_D + t_N) / 1000        [kWh/a]
    W_P = parasitic energy (controls standby, emergency charging)   [kWh/a]
    LENI = (W_L + W_P) / A                                   [kWh/(m²·a)]

P_n the installed power (W), t_D and t_N the annual operating hours with and without daylight,
F_C the constant-illuminance factor (1 without such control), F_O the occupancy-dependency
factor and F_D the daylight-dependency factor (1 without presence or daylight control), A the
floor area. The designer gives the hours and factors in the scene's ``metadata.report.energy``
(docs/scene-format.md); the report states every input next to the result."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

#: Hours in a year (EN 15193-1's t_y).
YEAR_HOURS = 8760.0


class EnergyInputError(ValueError):
    """A value of ``metadata.report.energy`` that LENI cannot use; the message names it."""


@dataclass
class EnergyInputs:
    """LENI's inputs as the designer gave them (defaults: no control, no parasitic load)."""

    daylight_hours: float
    night_hours: float
    constant_illuminance_factor: float = 1.0
    occupancy_factor: float = 1.0
    daylight_dependency_factor: float = 1.0
    parasitic_kwh_m2: float = 0.0
    area_m2: Optional[float] = None


@dataclass
class Leni:
    """A LENI estimate with what went into it."""

    inputs: EnergyInputs
    power_w: float
    area_m2: float
    area_label: str  # what the area is: the designer's floor area, or a calculation area
    lighting_kwh: float
    parasitic_kwh: float

    @property
    def total_kwh(self) -> float:
        return self.lighting_kwh + self.parasitic_kwh

    @property
    def leni_kwh_m2(self) -> float:
        return self.total_kwh / self.area_m2


#: Field, (lowest, highest) allowed, required.
_FIELDS: Tuple[Tuple[str, Tuple[float, float], bool], ...] = (
    ("daylight_hours", (0.0, YEAR_HOURS), True), ("night_hours", (0.0, YEAR_HOURS), True),
    ("constant_illuminance_factor", (0.0, 1.0), False), ("occupancy_factor", (0.0, 1.0), False),
    ("daylight_dependency_factor", (0.0, 1.0), False), ("parasitic_kwh_m2", (0.0, 1e4), False),
    ("area_m2", (1e-9, 1e12), False))


def read_inputs(block: Any, where: str = "metadata.report.energy") -> Optional[EnergyInputs]:
    """The energy inputs of a scene's ``metadata.report.energy`` (None when absent);
    EnergyInputError naming the field for a value out of range, a missing hour count or an
    unknown key (a typo would silently drop a control factor)."""
    if block is None:
        return None
    if not isinstance(block, dict):
        raise EnergyInputError(f"{where}: must be an object (got {type(block).__name__})")
    known = {name for name, _, _ in _FIELDS}
    unknown = sorted(set(block) - known)
    if unknown:
        raise EnergyInputError(f"{where}.{unknown[0]}: unknown key (known: "
                               f"{', '.join(sorted(known))})")
    values: Dict[str, float] = {}
    for name, (low, high), required in _FIELDS:
        value = block.get(name)
        if value is None:
            if required:
                raise EnergyInputError(f"{where}.{name}: missing (the annual operating hours "
                                       "with and without daylight are both needed)")
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value) or not low <= value <= high:
            raise EnergyInputError(f"{where}.{name}: must be a number in {low:g} … {high:g} "
                                   f"(got {value!r})")
        values[name] = float(value)
    hours = values["daylight_hours"] + values["night_hours"]
    if hours > YEAR_HOURS:
        raise EnergyInputError(f"{where}: daylight_hours + night_hours must not exceed "
                               f"{YEAR_HOURS:g} h (got {hours:g})")
    return EnergyInputs(**values)


def leni(inputs: EnergyInputs, power_w: float, area_m2: float, area_label: str) -> Leni:
    """LENI for ``power_w`` installed over ``area_m2`` (the module docstring's formula)."""
    lighting = power_w * inputs.constant_illuminance_factor * inputs.occupancy_factor * (
        inputs.daylight_hours * inputs.daylight_dependency_factor + inputs.night_hours) / 1000.0
    return Leni(inputs, power_w, area_m2, area_label, lighting,
                inputs.parasitic_kwh_m2 * area_m2)


def leni_area(inputs: EnergyInputs, horizontal: List[Tuple[str, float]],
              floor_m2: Optional[float] = None) -> Optional[Tuple[float, str]]:
    """The area LENI is per, with what it is: the designer's ``area_m2`` (EN 15193-1's useful
    floor area: the right input); else the floor area inside the walls that the model's plan
    encloses around the calculation grids (``floor_m2``, section.room_floor_area); else the
    largest upward-facing calculation grid's, said as such (a grid usually leaves a border
    along the walls, so LENI comes out somewhat high); None when none of them exists."""
    if inputs.area_m2 is not None:
        return inputs.area_m2, "floor area as stated"
    if floor_m2 is not None and floor_m2 > 0:
        return floor_m2, ("floor area inside the walls, measured on the plan: no floor area "
                          "was stated")
    if not horizontal:
        return None
    label, area = max(horizontal, key=lambda la: la[1])
    return area, (f"area of the calculation area {label}: no floor area was stated and the "
                  "plan shows no walls enclosing it")


def power_density(power_w: float, area_m2: float, em_lux: Optional[float]
                  ) -> Tuple[float, Optional[float]]:
    """(W/m², W/m² per 100 lx) of ``power_w`` over ``area_m2`` lit to ``em_lux``."""
    density = power_w / area_m2
    return density, density / (em_lux / 100.0) if em_lux else None
