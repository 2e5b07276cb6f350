# SPDX-License-Identifier: LGPL-2.1-or-later
"""A year of daylight (``lightsolver.annual/1``: the ``annual.json`` of ``lightsolver annual``
or the ``summary`` of ``lightsolver.annual``; docs/daylight.md, "A year of daylight") as a typed
view: the weather file and its hash, the sky and the trace, and per grid its annual metrics with
their intervals (IES LM-83 sDA and ASE, DA, UDI, hours above thresholds, EN 17037's illuminance
method) and per-cell arrays. The hourly arrays (``annual.npz``) are read by :func:`load_hours`
(numpy), the only part that needs it."""
from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Union

from pathlib import Path

from .layout import ResultsError, finite

ANNUAL_FORMAT = "lightsolver.annual/1"
#: The schema's file name (docs/schemas/; copied beside this package by CMake).
SCHEMA_NAME = "annual.schema.json"
VERDICTS = ("pass", "fail", "undecided")


@dataclass(frozen=True)
class Interval:
    """An annual metric with its interval at the run's confidence (low <= estimate <= high)."""

    estimate: Optional[float]
    low: Optional[float] = None
    high: Optional[float] = None


@dataclass(frozen=True)
class CellIntervals:
    """One metric per cell (row by row, index = iv * nu + iu) with its interval per cell."""

    estimate: List[float]
    low: List[float]
    high: List[float]


@dataclass(frozen=True)
class En17037Criterion:
    """E_T over 50 % (target) or E_TM over 95 % (minimum) of the area: the fraction of daylight
    hours at which the grid reaches it, needed >= half."""

    illuminance_lx: Optional[float]
    area_percent: Optional[float]
    hours_fraction: Interval
    verdict: str


@dataclass(frozen=True)
class En17037Level:
    level: str  # "minimum", "medium", "high"
    target: En17037Criterion
    minimum: En17037Criterion
    verdict: str


@dataclass(frozen=True)
class ElectricBeside:
    """The grid's electric light beside the daylight (annual.json ``grids[i].electric``): the
    task's illuminance, the electric light at full output, the occupied hours at which daylight
    misses the target and the mean output a daylight-linked dimmer would need (0 … 1)."""

    target_lx: Optional[float]
    electric_lx: Interval
    occupied_hours: Optional[int]
    hours_below_target: Interval
    mean_output_fraction: Interval


def _electric(entry: Any) -> Optional[ElectricBeside]:
    if not isinstance(entry, dict):
        return None
    return ElectricBeside(finite(entry.get("target_lx")), _interval(entry.get("electric_lx")),
                          _int(entry.get("occupied_hours")),
                          _interval(entry.get("hours_below_target")),
                          _interval(entry.get("mean_output_fraction")))


@dataclass(frozen=True)
class AnnualGrid:
    """One grid's year."""

    name: str
    nu: int
    nv: int
    area_m2: Optional[float]
    occupied_hours: Optional[int]
    daylight_hours: Optional[int]
    sda_percent: Interval
    sda_nominal_verdict: str  # against LM-83's 55 %
    sda_preferred_verdict: str  # against 75 %
    ase_percent: Optional[float]  # exact (shadow rays); None without sun
    ase_verdict: str
    da_fraction: Interval
    udi_below_fraction: Interval
    udi_useful_fraction: Interval
    udi_above_fraction: Interval
    udi_useful_alt_fraction: Interval
    udi_above_alt_fraction: Interval
    hours_above: Dict[float, Interval]  # threshold lx -> area-weighted mean hours
    en17037: List[En17037Level]
    options: Dict[str, Any]
    cell_da_fraction: CellIntervals
    cell_udi_useful_fraction: CellIntervals
    cell_sda_verdict: List[str]
    cell_ase_hours: List[int]
    cell_hours_above: Dict[float, CellIntervals] = field(default_factory=dict)
    electric: Optional[ElectricBeside] = None  # None: the scene has no electric luminaire


@dataclass(frozen=True)
class Weather:
    file: str
    sha256: str
    location: str
    region: str
    country: str
    source: str
    latitude_deg: Optional[float]
    longitude_deg: Optional[float]
    utc_offset_h: Optional[float]
    hours: Optional[int]
    sky_hours: Optional[int]
    sky_from: str  # "irradiance" (Perez efficacies) or "illuminance"


@dataclass(frozen=True)
class AnnualResults:
    weather: Weather
    mf: Optional[int]
    patches: Optional[int]
    north_deg: Optional[float]
    ground_reflectance: Optional[float]
    photons: Optional[int]
    backend: str
    stop_reason: str
    seconds: Dict[str, float]
    occupied_hours: Optional[int]
    occupancy: str
    daylight_hours: Optional[int]
    confidence: Optional[float]
    blinds_transmittance: Optional[float]
    grids: List[AnnualGrid]
    warnings: List[str]
    seed: Optional[int] = None
    decide: bool = False

    def grid(self, name: str) -> AnnualGrid:
        for g in self.grids:
            if g.name == name:
                return g
        raise KeyError(name)


def _interval(entry: Any) -> Interval:
    entry = entry if isinstance(entry, dict) else {}
    return Interval(finite(entry.get("estimate")), finite(entry.get("low")),
                    finite(entry.get("high")))


def _cells(entry: Any) -> CellIntervals:
    entry = entry if isinstance(entry, dict) else {}
    return CellIntervals(*(list(map(float, entry.get(k, []))) for k in ("estimate", "low", "high")))


def _verdict(v: Any) -> str:
    return v if v in VERDICTS else "undecided"


def _int(v: Any) -> Optional[int]:
    x = finite(v)
    return None if x is None else int(x)


def _criterion(entry: Any) -> En17037Criterion:
    entry = entry if isinstance(entry, dict) else {}
    return En17037Criterion(finite(entry.get("illuminance_lx")), finite(entry.get("area_percent")),
                            _interval(entry.get("hours_fraction")), _verdict(entry.get("verdict")))


def _grid(entry: Dict[str, Any]) -> AnnualGrid:
    m = entry.get("metrics", {})
    cells = m.get("cells", {})
    hours_above = {float(h["threshold_lx"]): _interval(h.get("hours"))
                   for h in m.get("hours_above", []) if isinstance(h, dict)}
    cell_hours = {float(h["threshold_lx"]): _cells(h.get("hours"))
                  for h in cells.get("hours_above", []) if isinstance(h, dict)}
    levels = [En17037Level(str(e.get("level", "")), _criterion(e.get("target")),
                           _criterion(e.get("minimum")), _verdict(e.get("verdict")))
              for e in m.get("en17037", []) if isinstance(e, dict)]
    return AnnualGrid(
        name=str(entry.get("name", "")), nu=int(entry.get("nu", 1)), nv=int(entry.get("nv", 1)),
        area_m2=finite(entry.get("area_m2")), occupied_hours=_int(m.get("occupied_hours")),
        daylight_hours=_int(m.get("daylight_hours")), sda_percent=_interval(m.get("sda_percent")),
        sda_nominal_verdict=_verdict(m.get("sda_nominal_verdict")),
        sda_preferred_verdict=_verdict(m.get("sda_preferred_verdict")),
        ase_percent=finite(m.get("ase_percent")), ase_verdict=_verdict(m.get("ase_verdict")),
        da_fraction=_interval(m.get("da_fraction")),
        udi_below_fraction=_interval(m.get("udi_below_fraction")),
        udi_useful_fraction=_interval(m.get("udi_useful_fraction")),
        udi_above_fraction=_interval(m.get("udi_above_fraction")),
        udi_useful_alt_fraction=_interval(m.get("udi_useful_alt_fraction")),
        udi_above_alt_fraction=_interval(m.get("udi_above_alt_fraction")),
        hours_above=hours_above, en17037=levels, options=dict(m.get("options", {})),
        cell_da_fraction=_cells(cells.get("da_fraction")),
        cell_udi_useful_fraction=_cells(cells.get("udi_useful_fraction")),
        cell_sda_verdict=[_verdict(v) for v in cells.get("sda_verdict", [])],
        cell_ase_hours=[int(v) for v in cells.get("ase_hours") or []],
        cell_hours_above=cell_hours, electric=_electric(entry.get("electric")))


_SCHEMA: Optional[Dict[str, Any]] = None


def annual_schema() -> Optional[Dict[str, Any]]:
    """docs/schemas/annual.schema.json, or None where neither copy is found."""
    global _SCHEMA
    if _SCHEMA is None:
        here = Path(__file__).resolve().parent
        for path in (here / SCHEMA_NAME, here.parents[2] / "docs" / "schemas" / SCHEMA_NAME):
            if path.is_file():
                _SCHEMA = json.loads(path.read_text(encoding="utf-8"))
                break
    return _SCHEMA


def check_annual(doc: Any) -> List[str]:
    """What in ``doc`` breaks the annual schema ("path: message" each; empty: none). Without
    ``jsonschema`` or the schema file only the format is checked."""
    if not isinstance(doc, dict):
        return ["not a JSON object"]
    if doc.get("format") != ANNUAL_FORMAT:
        return [f"format: expected {ANNUAL_FORMAT!r}, got {doc.get('format')!r}"]
    found = annual_schema()
    try:
        import jsonschema
    except ImportError:
        return []
    if found is None:
        return []
    validator = jsonschema.Draft202012Validator(found)
    return [f"{'/'.join(map(str, e.absolute_path)) or '(top)'}: {e.message}"
            for e in sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path))]


def read_annual(source: Union[str, os.PathLike, Dict[str, Any]],
                check_schema: bool = True) -> AnnualResults:
    """The view of an annual.json (a path, or the parsed dict). ResultsError for another format,
    a file that is not JSON, or (``check_schema``, where jsonschema is installed) a document
    that breaks docs/schemas/annual.schema.json, naming the first fields that do."""
    if isinstance(source, dict):
        doc = source
    else:
        try:
            with open(source, encoding="utf-8") as f:
                doc = json.load(f)
        except (OSError, ValueError) as e:
            raise ResultsError(f"{source}: not an annual results file ({e})") from e
    where = "the annual results" if isinstance(source, dict) else str(source)
    if not isinstance(doc, dict) or doc.get("format") != ANNUAL_FORMAT:
        raise ResultsError(f"{where}: not {ANNUAL_FORMAT} (format {doc.get('format')!r})"
                           if isinstance(doc, dict) else f"{where}: not a JSON object")
    problems = check_annual(doc) if check_schema else []
    if problems:
        more = f" (and {len(problems) - 3} more)" if len(problems) > 3 else ""
        raise ResultsError(f"{where}: breaks the annual results schema: "
                           f"{'; '.join(problems[:3])}{more}")
    w = doc.get("weather", {})
    weather = Weather(str(w.get("file", "")), str(w.get("sha256", "")), str(w.get("location", "")),
                      str(w.get("region", "")), str(w.get("country", "")), str(w.get("source", "")),
                      finite(w.get("latitude_deg")), finite(w.get("longitude_deg")),
                      finite(w.get("utc_offset_h")), _int(w.get("hours")),
                      _int(w.get("sky_hours")), str(w.get("sky_from", "")))
    sky, trace = doc.get("sky", {}), doc.get("trace", {})
    occupancy = doc.get("occupancy", {})
    return AnnualResults(
        weather=weather, mf=_int(sky.get("mf")), patches=_int(sky.get("patches")),
        north_deg=finite(sky.get("north_deg")),
        ground_reflectance=finite(sky.get("ground_reflectance")),
        photons=_int(trace.get("photons")), backend=str(trace.get("backend", "")),
        stop_reason=str(trace.get("stop_reason", "")),
        seconds={k: float(v) for k, v in doc.get("seconds", {}).items() if finite(v) is not None},
        occupied_hours=_int(occupancy.get("hours")), occupancy=str(occupancy.get("schedule", "")),
        daylight_hours=_int(doc.get("daylight_hours")), confidence=finite(doc.get("confidence")),
        blinds_transmittance=finite(doc.get("blinds_transmittance")),
        grids=[_grid(g) for g in doc.get("grids", []) if isinstance(g, dict)],
        warnings=[str(x) for x in doc.get("warnings", [])], seed=_int(trace.get("seed")),
        decide=trace.get("decide") is True)


def load_hours(npz_path: Union[str, os.PathLike], grid_index: int) -> Dict[str, Any]:
    """Grid `grid_index`'s hourly arrays from annual.npz (numpy): mean, low, high and, with a
    sun, direct_sun (hours x cells, lx, float32), and month_day_hour (hours x 3)."""
    import numpy as np  # only here: the view above needs none

    with np.load(npz_path) as z:
        prefix = f"g{grid_index}_"
        out = {k[len(prefix):]: z[k] for k in z.files if k.startswith(prefix)}
        if not out:
            raise ResultsError(f"{npz_path}: no grid {grid_index}")
        out["month_day_hour"] = z["month_day_hour"]
    return out
