# SPDX-License-Identifier: LGPL-2.1-or-later
"""A year of daylight in the report (issue 27; docs/report.md, "A year of daylight"): the annual
results of ``lightsolver annual`` (annual.json, read by ``lightsolver_results.read_annual``)
as the report prints them — the weather data with its fingerprint, the sky, occupancy and
daylight hours, and per grid the IES LM-83 metrics (sDA300/50%, ASE1000,250h), mean DA300, UDI
and EN 17037's illuminance method with their intervals and verdicts, and plans of DA300 and of
the hours of direct sun per cell. Plain data; ``templates/annual.html.j2`` lays it out and
``annual_plots.py`` draws the plans.

The annual results must belong to the scene: each of their grids a grid of the scene with the
same cells (they record no hash of the scene, so this is the check there is)."""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np

import lightsolver_results
from lightsolver_report import fmt
from lightsolver_report.wording import Namer, client_notes
from lightsolver_results.annual import AnnualGrid, AnnualResults, Interval

PathLike = Union[str, "os.PathLike[str]"]
#: Characters of the weather file's SHA-256 printed large (the whole hash in small print).
SHORT_HASH = 12
#: IES LM-83-12's sDA300/50% thresholds (nominally accepted, preferred) and ASE's limit, %.
SDA_NOMINAL, SDA_PREFERRED, ASE_LIMIT = 55.0, 75.0, 10.0


class AnnualError(ValueError):
    """The annual results cannot be reported with this scene; the message says why."""


@dataclass
class UdiBand:
    """A UDI band: what it is called, its illuminance range, the fraction of occupied hours."""

    name: str
    band: str
    fraction: Interval


@dataclass
class AnnualGridView:
    """One grid's year as the report prints it."""

    name: str
    label: str
    data: AnnualGrid
    #: DA300 per cell in percent and the cells whose sDA verdict is undecided, shape (nv, nu).
    da_percent: np.ndarray
    undecided: np.ndarray
    #: Occupied hours of direct sun above 1000 lx per cell (exact), None without a sun.
    ase_hours: Optional[np.ndarray]
    udi: List[UdiBand] = field(default_factory=list)
    udi_alt: List[UdiBand] = field(default_factory=list)
    #: The scene target's corner and edges (for the plans), None where the scene lacks them.
    geometry: Optional[Dict[str, Any]] = None
    da_plan_svg: str = ""
    ase_plan_svg: str = ""

    @property
    def cells(self) -> int:
        return int(self.da_percent.size)

    @property
    def undecided_count(self) -> int:
        return int(np.count_nonzero(self.undecided))

    @property
    def passing_count(self) -> int:
        return sum(v == "pass" for v in self.data.cell_sda_verdict)

    @property
    def ase_cells_over(self) -> Optional[int]:
        """Cells with more than the 250 h of direct sun ASE counts."""
        if self.ase_hours is None:
            return None
        return int(np.count_nonzero(self.ase_hours > self.data.options.get("ase_hours", 250)))


@dataclass
class AnnualSection:
    """The weather, the sky, the hours and the grids of a year of daylight."""

    weather_file: str
    sha256: str
    place: str
    site: str
    source: str
    hours: Optional[int]
    sky_hours: Optional[int]
    sky_from: str
    mf: Optional[int]
    sky_patches: Optional[int]
    ground_reflectance: Optional[float]
    north: str
    occupancy: str
    occupied_hours: Optional[int]
    daylight_hours: Optional[int]
    confidence: Optional[float]
    blinds_transmittance: Optional[float]
    photons: Optional[int]
    seed: Optional[int]
    backend: str
    decide: bool
    stop_reason: str
    seconds: Dict[str, float]
    grids: List[AnnualGridView]
    #: The annual trace's remarks in the client's words (wording.client_notes).
    warnings: List[str]

    @property
    def sha256_short(self) -> str:
        return self.sha256[:SHORT_HASH]

    @property
    def tregenza(self) -> bool:
        return self.mf == 1


def _site(lat: Optional[float], lon: Optional[float], offset: Optional[float]) -> str:
    """41.98° N, 87.92° W, local standard time UTC−6 h."""
    if lat is None or lon is None:
        return "–"
    text = (f"{abs(lat):.2f}° {'N' if lat >= 0 else 'S'}, "
            f"{abs(lon):.2f}° {'E' if lon >= 0 else 'W'}")
    if offset is not None:
        sign = "+" if offset >= 0 else "\u2212"
        text += f", local standard time UTC{sign}{abs(offset):g}\u00a0h"
    return text


def _north(north_deg: Optional[float]) -> str:
    if north_deg is None or abs(north_deg) < 1e-9:
        return "true north along the model's +y axis"
    return (f"true north turned {abs(north_deg):g}° "
            f"{'counter-clockwise' if north_deg > 0 else 'clockwise'} from the model's +y "
            "axis (seen from above)")


def _occupancy(schedule: str) -> str:
    """The schedule in client words (LM-83's default named as such)."""
    if "LM-83" in schedule:
        return "IES LM-83: every day 8:00–18:00 local standard time"
    return schedule.replace("-", "–") if schedule else "–"


def _cells(values: List[float], nu: int, nv: int, what: str, name: str) -> np.ndarray:
    if len(values) != nu * nv:
        raise AnnualError(f"grid '{name}': {len(values)} values of {what} for {nu} × {nv} cells")
    return np.asarray(values, dtype=float).reshape(nv, nu)


def _grid_view(grid: AnnualGrid, scene_target: Dict[str, Any],
               labels: Dict[str, str]) -> AnnualGridView:
    nu, nv = grid.nu, grid.nv
    da = _cells(grid.cell_da_fraction.estimate, nu, nv, "DA", grid.name) * 100.0
    verdicts = grid.cell_sda_verdict
    undecided = _cells([1.0 if v == "undecided" else 0.0 for v in verdicts], nu, nv,
                       "sDA verdicts", grid.name) > 0.5
    ase = (_cells([float(h) for h in grid.cell_ase_hours], nu, nv, "ASE hours", grid.name)
           if grid.ase_percent is not None and grid.cell_ase_hours else None)
    o = grid.options
    low, high, alt = (o.get("udi_low_lx", 100.0), o.get("udi_high_lx", 2000.0),
                      o.get("udi_high_alt_lx", 3000.0))
    view = AnnualGridView(grid.name, str(labels.get(grid.name, grid.name)), grid, da, undecided,
                          ase)
    view.udi = [UdiBand("fell short", f"below {low:g} lx", grid.udi_below_fraction),
                UdiBand("useful", f"{low:g}–{high:g} lx", grid.udi_useful_fraction),
                UdiBand("exceeded", f"above {high:g} lx", grid.udi_above_fraction)]
    view.udi_alt = [UdiBand(f"useful, to {alt:g} lx", f"{low:g}–{alt:g} lx",
                            grid.udi_useful_alt_fraction),
                    UdiBand(f"exceeded {alt:g} lx", f"above {alt:g} lx",
                            grid.udi_above_alt_fraction)]
    if all(k in scene_target for k in ("corner", "edge1", "edge2")):
        view.geometry = {k: scene_target[k] for k in ("corner", "edge1", "edge2")}
    return view


def _scene_grids(scene: Dict[str, Any]) -> Dict[str, Dict[str, Any]]:
    return {str(t.get("name")): t for t in scene.get("targets", [])
            if isinstance(t, dict) and t.get("type") == "grid"}


def _belongs(grid: AnnualGrid, grids: Dict[str, Dict[str, Any]], where: str) -> Dict[str, Any]:
    """The scene's grid of that name with the same cells, else AnnualError."""
    target = grids.get(grid.name)
    if target is None:
        raise AnnualError(f"{where}: grid '{grid.name}' is not a grid of the scene: the annual "
                          "results were calculated for another model")
    cells = target.get("cells")
    same = (isinstance(cells, list) and len(cells) == 2
            and all(isinstance(c, (int, float)) and not isinstance(c, bool) for c in cells)
            and [int(c) for c in cells] == [grid.nu, grid.nv])
    if not same:
        raise AnnualError(f"{where}: grid '{grid.name}' has {grid.nu} × {grid.nv} cells, the "
                          f"scene's {cells}: the annual results were calculated for another "
                          "state of the model")
    return target


def read_section(source: Union[PathLike, Dict[str, Any]], scene: Dict[str, Any],
                 labels: Dict[str, str]) -> AnnualSection:
    """The annual section of ``source`` (an annual.json path or its dict) for ``scene``.
    AnnualError for a file that cannot be read, breaks the annual schema, holds no grid, or
    whose grids are not the scene's."""
    where = "the annual results" if isinstance(source, dict) else str(source)
    try:
        view: AnnualResults = lightsolver_results.read_annual(source)
    except lightsolver_results.ResultsError as exc:
        raise AnnualError(str(exc)) from exc
    if not view.grids:
        raise AnnualError(f"{where}: no grid: there is nothing to report")
    grids = _scene_grids(scene)
    w = view.weather
    place = ", ".join(p for p in (w.location, w.region, w.country) if p) or "–"
    return AnnualSection(
        weather_file=w.file, sha256=w.sha256, place=place,
        site=_site(w.latitude_deg, w.longitude_deg, w.utc_offset_h), source=w.source or "–",
        hours=w.hours, sky_hours=w.sky_hours, sky_from=w.sky_from, mf=view.mf,
        sky_patches=view.patches, ground_reflectance=view.ground_reflectance,
        north=_north(view.north_deg), occupancy=_occupancy(view.occupancy),
        occupied_hours=view.occupied_hours, daylight_hours=view.daylight_hours,
        confidence=view.confidence, blinds_transmittance=view.blinds_transmittance,
        photons=view.photons, seed=view.seed, backend=view.backend, decide=view.decide,
        stop_reason=view.stop_reason, seconds=dict(view.seconds),
        grids=[_grid_view(g, _belongs(g, grids, where), labels) for g in view.grids],
        warnings=[n.text for n in client_notes(view.warnings, Namer(labels))])


#: The section's number formats (lightsolver_report.fmt, where the templates get them).
fraction_text, percent_text = fmt.frac, fmt.pct


def attach_pictures(section: AnnualSection) -> None:
    """Each grid's plans of DA300 and of the hours of direct sun (SVG text)."""
    from lightsolver_report import annual_plots

    for i, grid in enumerate(section.grids):
        if grid.geometry is None:
            continue
        grid.da_plan_svg = annual_plots.da_plan_svg(grid, f"daplan{i}")
        if grid.ase_hours is not None:
            grid.ase_plan_svg = annual_plots.ase_plan_svg(grid, f"aseplan{i}")


def grid_extent(geometry: Dict[str, Any]) -> Tuple[float, float, float, float, str, str]:
    """(origin u, origin v, size u, size v, axis u, axis v) of a grid: world coordinates where
    its edges run along the model's axes, else its own u and v from its corner."""
    e1 = np.asarray(geometry["edge1"], dtype=float)
    e2 = np.asarray(geometry["edge2"], dtype=float)
    corner = np.asarray(geometry["corner"], dtype=float)
    size_u, size_v = float(np.linalg.norm(e1)), float(np.linalg.norm(e2))

    def axis(edge: np.ndarray, length: float) -> Optional[int]:
        for a in range(3):
            if length > 0 and edge[a] > 0 and abs(edge[a] - length) <= 1e-9 * length:
                return a
        return None

    a1, a2 = axis(e1, size_u), axis(e2, size_v)
    if a1 is not None and a2 is not None and a1 != a2:
        return float(corner[a1]), float(corner[a2]), size_u, size_v, "xyz"[a1], "xyz"[a2]
    return 0.0, 0.0, size_u, size_v, "u", "v"
