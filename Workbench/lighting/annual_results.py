# SPDX-License-Identifier: LGPL-2.1-or-later
"""A year of daylight as the workbench shows it: the stored summary of an annual daylight
analysis (objects/annual.py) read through ``lightsolver_results.read_annual`` (never its keys
by hand), its lines for the panel and the property editor (sDA300/50% with its interval and
verdicts, ASE, DA300, UDI, EN 17037's levels, the weather file), and the per-cell maps with
their colour scales (DA300, UDI 100-2000 lx, ASE hours, sDA verdict per cell). App code (no
GUI): the 3D view's painting (viewproviders/annual_coloring.py) and the panel use it."""
from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence

from lighting.colormap import Scale, nice_max

#: A cell's sDA verdict -> its value on the verdict map.
VERDICT_VALUE = {"fail": 0.0, "undecided": 1.0, "pass": 2.0}
#: Their colours: distinct and readable for colour-blind eyes (blue pass, orange undecided,
#: dark red fail: never a red/green pair alone).
VERDICT_COLOUR = {0.0: (0.7, 0.1, 0.1), 1.0: (1.0, 0.65, 0.0), 2.0: (0.15, 0.4, 0.9)}


class VerdictScale(Scale):
    """The sDA verdict map: three colours, not a gradient (0 fail, 1 undecided, 2 pass)."""

    def __init__(self) -> None:
        super().__init__(0.0, 2.0, "Verdict")

    def colour(self, lux: float) -> tuple:
        return VERDICT_COLOUR[min(VERDICT_VALUE.values(), key=lambda v: abs(v - lux))]

    def ticks(self, count: int = 3) -> List[float]:
        return [0.0, 1.0, 2.0]


def read(summary: Optional[Dict[str, Any]]) -> Optional[Any]:
    """The typed view (``lightsolver_results.AnnualResults``) of a stored summary, or None
    (none, or one the reader refuses)."""
    if not summary:
        return None
    from lighting.messages import LightingError
    from lighting.solver.results import reader

    try:
        module = reader()
    except LightingError:  # no reader: the stored summary stays, unread until there is one
        return None
    try:
        return module.read_annual(summary)
    except module.ResultsError:
        return None


def grid_of(typed: Optional[Any], target_name: str) -> Optional[Any]:
    """The ``AnnualGrid`` of a grid target (the scene names grids by object Name), or None."""
    for grid in (typed.grids if typed is not None else []):
        if grid.name == target_name:
            return grid
    return None


def _percent(x: Optional[float], scale: float = 1.0, digits: int = 1) -> str:
    return "-" if x is None else f"{float(x) * scale:.{digits}f} %"


def interval_text(iv: Any, scale: float = 1.0, digits: int = 1) -> str:
    """"62.3 % (58.0 - 66.7 %)"; "-" without an estimate."""
    if iv is None or iv.estimate is None:
        return "-"
    value = _percent(iv.estimate, scale, digits)
    if iv.low is None or iv.high is None:
        return value
    return f"{value} ({iv.low * scale:.{digits}f} - {iv.high * scale:.{digits}f} %)"


def verdict_word(verdict: str) -> str:
    """"pass", "FAIL" or "undecided"."""
    return {"pass": "pass", "fail": "FAIL"}.get(verdict, "undecided")


def grid_lines(grid: Any, label: str) -> List[str]:
    """The panel's lines for one grid: sDA with its interval and LM-83 verdicts, ASE, mean
    DA300 and UDI (each with its interval), EN 17037's levels."""
    opts = grid.options
    nominal = opts.get("sda_nominal_percent", 55.0)
    preferred = opts.get("sda_preferred_percent", 75.0)
    lines = [f"{label}: {len(grid.cell_sda_verdict)} cells, {grid.occupied_hours or 0} "
             "occupied hours",
             f"  sDA300/50%: {interval_text(grid.sda_percent)}; LM-83 nominal (>= "
             f"{nominal:.0f} %): {verdict_word(grid.sda_nominal_verdict)}, preferred (>= "
             f"{preferred:.0f} %): {verdict_word(grid.sda_preferred_verdict)}"]
    undecided = sum(1 for v in grid.cell_sda_verdict if v == "undecided")
    if undecided:
        lines.append(f"  cells undecided (DA300 too near 50 %): {undecided}")
    if grid.ase_percent is None:
        lines.append("  ASE1000,250h: - (no direct sun in the run)")
    else:
        limit = opts.get("ase_maximum_percent", 10.0)
        lines.append(f"  ASE1000,250h: {grid.ase_percent:.1f} % (exact: shadow rays), limit "
                     f"{limit:.0f} %: {verdict_word(grid.ase_verdict)}")
    lines.append(f"  mean DA300: {interval_text(grid.da_fraction, 100.0)} of occupied hours")
    lines.append(f"  mean UDI 100-2000 lx: {interval_text(grid.udi_useful_fraction, 100.0)} "
                 f"(below {_percent(grid.udi_below_fraction.estimate, 100.0)}, above "
                 f"{_percent(grid.udi_above_fraction.estimate, 100.0)})")
    electric = getattr(grid, "electric", None)
    if electric is not None:
        h = electric.hours_below_target
        hours = "-" if h.estimate is None else (
            f"{h.estimate:.0f} h" + ("" if h.low is None or h.high is None
                                     else f" ({h.low:.0f} - {h.high:.0f} h)"))
        lines.append(f"  electric beside daylight: daylight below {electric.target_lx or 0:.0f} lx "
                     f"in {hours} of {electric.occupied_hours} occupied hours; dimmer output "
                     f"{interval_text(electric.mean_output_fraction, 100.0)}")
    for level in grid.en17037:
        t, m = level.target, level.minimum
        lines.append(f"  EN 17037 {level.level}: {verdict_word(level.verdict)} "
                     f"({t.illuminance_lx or 0:.0f} lx over {t.area_percent or 0:.0f} %: "
                     f"{interval_text(t.hours_fraction, 100.0, 0)} of daylight hours; "
                     f"{m.illuminance_lx or 0:.0f} lx over {m.area_percent or 0:.0f} %: "
                     f"{interval_text(m.hours_fraction, 100.0, 0)})")
    return lines


def weather_line(typed: Any) -> str:
    """"Weather: Chicago Ohare Intl Ap, IL, USA (TMY3; file X.epw, sha256 3cc3dc0c...)"."""
    w = typed.weather
    place = ", ".join(p for p in (w.location, w.region, w.country) if p)
    return (f"Weather: {place} ({w.source}; file {w.file}, sha256 {w.sha256[:16]}...), "
            f"{w.sky_hours or 0} hours with daylight")


def summary_lines(summary: Optional[Dict[str, Any]],
                  labels: Optional[Dict[str, str]] = None) -> List[str]:
    """Every line of a stored summary (empty without one): the weather, the trace, each grid
    (``labels``: grid name -> the label shown, default the name)."""
    typed = read(summary)
    if typed is None:
        return []
    lines = [weather_line(typed),
             f"Sky: {typed.patches or 0} patches (MF {typed.mf or 0}), north "
             f"{typed.north_deg or 0.0:g} deg; {typed.occupancy}; {typed.photons or 0:,} "
             f"photons ({typed.backend}), confidence {100 * (typed.confidence or 0):.0f} %"]
    for grid in typed.grids:
        lines += grid_lines(grid, (labels or {}).get(grid.name, grid.name))
    lines += [f"Warning: {w}" for w in typed.warnings]
    return lines


# -- maps ------------------------------------------------------------------------------------
def cell_values(grid: Any, kind: str) -> List[float]:
    """A grid's per-cell values for a map (row by row, as its cells): DA300 and UDI as
    fractions of occupied hours, ASE in hours, the sDA verdict as VERDICT_VALUE."""
    if kind == "DA300":
        return list(grid.cell_da_fraction.estimate)
    if kind == "UDI 100-2000 lx":
        return list(grid.cell_udi_useful_fraction.estimate)
    if kind == "ASE hours":
        return [float(h) for h in grid.cell_ase_hours]
    if kind == "sDA verdict":
        return [VERDICT_VALUE[v] for v in grid.cell_sda_verdict]
    raise ValueError(f"no annual map {kind!r}")


def scale(kind: str, values: Sequence[float], color_map: str = "Rainbow") -> Scale:
    """The colour scale of a map: fractions 0..1; ASE hours 0 to a round maximum (at least
    twice LM-83's 250 h, so 250 h sits mid-scale); the verdicts their three colours."""
    if kind == "sDA verdict":
        return VerdictScale()
    if kind == "ASE hours":
        return Scale(0.0, max(500.0, nice_max(max(values, default=0.0))), color_map)
    return Scale(0.0, 1.0, color_map)


#: Legend titles and digits per map.
LEGEND = {"DA300": ("DA300 [fraction of occupied hours]", 1),
          "UDI 100-2000 lx": ("UDI 100-2000 lx [fraction of occupied hours]", 1),
          "ASE hours": ("Direct sun > 1000 lx [occupied hours]", 0),
          "sDA verdict": ("sDA300/50% per cell: 0 fail, 1 undecided, 2 pass", 0)}
