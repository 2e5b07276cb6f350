# SPDX-License-Identifier: LGPL-2.1-or-later
"""Daylight in the report (issue 26; docs/report.md, "Daylight"): each daylight-factor grid's
statistics, requirements and EN 17037 verdicts (the results' ``daylight_factor``), the sky, the
sun and their openings as a schedule of their own (not luminaires: no lumens, watts or MF), and
the sunlight exposure of points (the results' top-level ``sunlight_exposure``). Plain data; the
template ``daylight.html.j2`` lays it out."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy as np

from lightsolver_report.fmt import finite
from lightsolver_results import Stat
from lightsolver_results.sunlight import sunlight_view

#: Luminaire types that are daylight: the daylight schedule lists them, the luminaire
#: schedule, installed power and LENI leave them out.
DAYLIGHT_TYPES = ("sky", "sun")
#: EN 17037:2018 Table A.1 (vertical and inclined openings): (E_T, E_TM) in lx per level.
EN17037 = {"minimum": (300.0, 100.0), "medium": (500.0, 300.0), "high": (750.0, 500.0)}
COMPASS16 = ("north", "north-north-east", "north-east", "east-north-east", "east",
             "east-south-east", "south-east", "south-south-east", "south", "south-south-west",
             "south-west", "west-south-west", "west", "west-north-west", "north-west",
             "north-north-west")

SunFn = Callable[..., Dict[str, Any]]


@dataclass
class DaylightFactor:
    """A daylight-factor grid's statistics (percent), the sky they refer to and the
    requirements they are judged against."""

    sky_label: str
    outside_lx: Optional[float]
    mean: Stat
    p50: Stat
    p95: Stat
    minimum: Stat
    #: The cells in percent, shape (nv, nu) as the grid's lux.
    percent: Optional[np.ndarray] = None
    level: Optional[str] = None  # EN 17037: minimum, medium, high
    median_diffuse_lx: Optional[float] = None
    target_percent: Optional[float] = None  # D_T, over 50 % of the area
    minimum_percent: Optional[float] = None  # D_TM, over 95 % of the area
    #: The requirement the designer set in place of the level's (True per key).
    target_given: bool = False
    minimum_given: bool = False
    sky: Optional["SkyRow"] = None

    @property
    def stats(self) -> List[Tuple[str, Stat]]:
        """(key, statistic) in print order; the keys of the verdicts they are judged by."""
        return [("df_mean", self.mean), ("df_target", self.p50), ("df_minimum", self.p95),
                ("df_min", self.minimum)]

    @property
    def level_illuminances(self) -> Optional[Tuple[float, float]]:
        """(E_T, E_TM) of the EN 17037 level, None without one."""
        return EN17037.get(self.level or "")


def _pct(entry: Dict[str, Any], stem: str) -> Stat:
    return Stat(finite(entry.get(f"{stem}_percent")), finite(entry.get(f"{stem}_ci_low_percent")),
                finite(entry.get(f"{stem}_ci_high_percent")))


def _cells(entry: Dict[str, Any], shape: Optional[Tuple[int, int]]) -> Optional[np.ndarray]:
    cells = entry.get("cells")
    if shape is None or not isinstance(cells, list) or len(cells) != shape[0] * shape[1]:
        return None
    values = [finite(c.get("percent")) if isinstance(c, dict) else None for c in cells]
    if any(v is None for v in values):
        return None
    return np.array(values, dtype=float).reshape(shape[1], shape[0])


def read_daylight_factor(entry: Any, req: Any, cells_uv: Optional[Tuple[int, int]],
                         labels: Dict[str, str], scene_req: Any = None) -> Optional[DaylightFactor]:
    """A grid's ``daylight_factor`` (docs/scene-format.md, "Results"), None where there is none.
    ``req`` is the resolved requirements echo; ``scene_req`` the scene's (which says whether a
    df_*_percent was the designer's own or derived from the level)."""
    if not isinstance(entry, dict):
        return None
    sky = str(entry.get("sky", ""))
    df = DaylightFactor(sky_label=labels.get(sky, sky),
                        outside_lx=finite(entry.get("outside_illuminance_lx")),
                        mean=Stat(finite(entry.get("mean_percent")),
                                  finite(entry.get("ci_low_percent")),
                                  finite(entry.get("ci_high_percent"))),
                        p50=_pct(entry, "p50"), p95=_pct(entry, "p95"),
                        minimum=_pct(entry, "min"), percent=_cells(entry, cells_uv))
    req = req if isinstance(req, dict) else {}
    scene_req = scene_req if isinstance(scene_req, dict) else {}
    level = req.get("en17037", scene_req.get("en17037"))
    df.level = str(level) if level in EN17037 else None
    df.median_diffuse_lx = finite(req.get("median_diffuse_lx",
                                          scene_req.get("median_diffuse_lx")))
    df.target_percent = finite(req.get("df_target_percent"))
    df.minimum_percent = finite(req.get("df_minimum_percent"))
    df.target_given = finite(scene_req.get("df_target_percent")) is not None
    df.minimum_given = finite(scene_req.get("df_minimum_percent")) is not None
    return df


# --- the daylight schedule ------------------------------------------------------------------

@dataclass
class Opening:
    """A sky's portal or a sun's opening: its area, which way it faces and its glazing."""

    number: int
    area_m2: float
    facing: str
    transmittance: Optional[float] = None  # τv at normal incidence; None: an open hole
    panes: Optional[int] = None
    frame_factor: float = 1.0
    maintenance_factor: float = 1.0

    @property
    def effective(self) -> float:
        """τv × frame × maintenance: the share of light at normal incidence that passes."""
        tau = 1.0 if self.transmittance is None else self.transmittance
        return tau * self.frame_factor * self.maintenance_factor


@dataclass
class SkyRow:
    """A ``sky`` luminaire as the daylight schedule prints it."""

    label: str
    model: str
    level: str
    ground_reflectance: float
    sun: str = ""  # the sun position the sky's luminance distribution uses ("" if none)
    openings: List[Opening] = field(default_factory=list)
    site: bool = False  # no portals: the whole sky over a site
    flux_lm: Optional[float] = None  # entering the room, as traced

    @property
    def opening_area_m2(self) -> float:
        return sum(o.area_m2 for o in self.openings)


@dataclass
class SunRow:
    """A ``sun`` luminaire: its position, direct normal illuminance and openings."""

    label: str
    when: str  # the date and time and site, or "" for a direction given
    elevation_deg: Optional[float]
    azimuth: str  # compass direction the sun is seen in
    direct_normal_lx: Optional[float]
    openings: List[Opening] = field(default_factory=list)
    flux_lm: Optional[float] = None


def compass(bearing: float) -> str:
    """A bearing (degrees clockwise from north) as a 16-point compass word and degrees."""
    bearing = bearing % 360.0
    return f"{COMPASS16[int(((bearing + 11.25) % 360.0) // 22.5)]} ({bearing:.0f}°)"


def _bearing(d: np.ndarray, north_deg: Optional[float]) -> Optional[str]:
    """Compass name of a horizontal direction (model frame), or its model axis angle."""
    if math.hypot(float(d[0]), float(d[1])) < 1e-9:
        return None
    phi = math.degrees(math.atan2(float(d[1]), float(d[0])))
    if north_deg is None:
        return f"{phi % 360.0:.0f}° from the model's x axis"
    return compass(90.0 + north_deg - phi)


def _openings(entries: Any, north_deg: Optional[float],
              toward_sun: Optional[np.ndarray] = None) -> List[Opening]:
    """Each opening's area, facing and glazing. A portal's edge1 × edge2 points into the room;
    a sun's own opening (corner, edge1, edge2) has no such sense: it faces the sun
    (``toward_sun``)."""
    out = []
    for i, portal in enumerate(entries if isinstance(entries, list) else []):
        try:
            e1 = np.asarray(portal["edge1"], dtype=float)
            e2 = np.asarray(portal["edge2"], dtype=float)
        except (KeyError, TypeError, ValueError):
            continue
        inward = np.cross(e1, e2)
        area = float(np.linalg.norm(inward))
        outward = -inward
        if toward_sun is not None and float(outward @ toward_sun) < 0.0:
            outward = inward
        if abs(outward[2]) > 0.98 * max(area, 1e-12):
            facing = "up (roof light)" if outward[2] > 0 else "down"
        else:
            facing = _bearing(outward, north_deg) or "–"
        opening = Opening(i + 1, area, facing)
        glazing = portal.get("glazing")
        if isinstance(glazing, dict):
            opening.transmittance = finite(glazing.get("transmittance"))
            opening.panes = int(glazing.get("panes", 1))
            opening.frame_factor = finite(glazing.get("frame_factor")) or 1.0
            opening.maintenance_factor = finite(glazing.get("maintenance_factor")) or 1.0
        out.append(opening)
    return out


SKY_MODELS = {"cie_overcast": "traditional CIE overcast sky (Moon & Spencer)",
              "uniform": "uniform sky", "perez": "Perez all-weather sky"}


def _sky_model(lum: Dict[str, Any]) -> str:
    model = str(lum.get("model", ""))
    if model == "cie":
        return f"CIE standard general sky, type {lum.get('cie_type', '–')} (ISO 15469)"
    return SKY_MODELS.get(model, model)


def _sky_level(lum: Dict[str, Any]) -> str:
    if finite(lum.get("diffuse_horizontal_lx")) is not None:
        return f"{float(lum['diffuse_horizontal_lx']):,.0f} lx diffuse horizontal".replace(
            ",", "\u202f")
    if finite(lum.get("zenith_luminance_cd_m2")) is not None:
        return f"zenith luminance {float(lum['zenith_luminance_cd_m2']):,.0f} cd/m²".replace(
            ",", "\u202f")
    perez = lum.get("perez")
    if isinstance(perez, dict):
        unit = "W/m²" if perez.get("units", "W/m2") == "W/m2" else "lx"
        return (f"diffuse horizontal {perez.get('diffuse_horizontal')} {unit}, direct normal "
                f"{perez.get('direct_normal')} {unit}")
    return "–"


def _toward(d: Any, north_deg: Optional[float]) -> Tuple[Optional[float], str]:
    """Elevation and compass bearing of a direction toward the sun."""
    try:
        v = np.asarray(d, dtype=float)
        v = v / float(np.linalg.norm(v))
    except (TypeError, ValueError, ZeroDivisionError):
        return None, "–"
    if not np.all(np.isfinite(v)):
        return None, "–"
    elevation = math.degrees(math.asin(max(-1.0, min(1.0, float(v[2])))))
    return elevation, _bearing(v, north_deg) or "overhead"


def _site(lat: Optional[float], lon: Optional[float]) -> str:
    """52.52° N, 13.40° E."""
    if lat is None or lon is None:
        return "–"
    north, east = "N" if lat >= 0 else "S", "E" if lon >= 0 else "W"
    return f"{abs(lat):.2f}° {north}, {abs(lon):.2f}° {east}"


def _local_time(text: str) -> str:
    """ISO 8601 local time with its zone as a client reads it: 2026-03-21 12:00 (UTC+01:00)."""
    date, _, rest = text.partition("T")
    for mark in ("+", "-", "Z"):
        if mark in rest:
            clock, _, zone = rest.partition(mark)
            zone = "UTC" if mark == "Z" else f"UTC{mark}{zone}"
            return f"{date} {clock[:5]} ({zone})"
    return f"{date} {rest[:5]}".strip()


def _sun_row(lum: Dict[str, Any], label: str, north_deg: Optional[float],
             sun_position: Optional[SunFn]) -> SunRow:
    row = SunRow(label=label, when="", elevation_deg=None, azimuth="–",
                 direct_normal_lx=finite(lum.get("illuminance_lx")))
    north = finite(lum.get("north_deg"))
    north = north if north is not None else north_deg
    site, time = lum.get("site"), lum.get("time")
    toward: Optional[np.ndarray] = None
    if isinstance(site, dict) and isinstance(time, str):
        lat, lon = finite(site.get("latitude_deg")), finite(site.get("longitude_deg"))
        row.when = f"{_local_time(time)}, {_site(lat, lon)}"
        if sun_position is not None and lat is not None and lon is not None:
            try:
                pos = sun_position(lat, lon, time, elevation_m=finite(site.get("elevation_m"))
                                   or 0.0, north_deg=north or 0.0)
                row.elevation_deg = float(pos["elevation_deg"])
                row.azimuth = compass(float(pos["azimuth_deg"]))
                toward = np.asarray(pos["direction"], dtype=float)
            except (ValueError, KeyError, TypeError):
                pass
    elif lum.get("direction") is not None:
        toward = -np.asarray(lum["direction"], dtype=float)
        row.elevation_deg, row.azimuth = _toward(toward, north)
    if isinstance(lum.get("portals"), list):  # docs/scene-format.md, "The sun"
        row.openings = _openings(lum["portals"], north_deg)
    else:
        row.openings = _openings([lum], north_deg, toward)
    return row


def build_schedule(scene: Dict[str, Any], traced_flux: Dict[str, float],
                   labels: Dict[str, str], sun_position: Optional[SunFn] = None
                   ) -> Tuple[List[SkyRow], List[SunRow]]:
    """The skies and suns of the scene, in scene order."""
    meta = scene.get("metadata") if isinstance(scene.get("metadata"), dict) else {}
    north_deg = finite(meta.get("north_deg"))
    skies: List[SkyRow] = []
    suns: List[SunRow] = []
    for lum in scene.get("luminaires", []):
        if not isinstance(lum, dict) or lum.get("type") not in DAYLIGHT_TYPES:
            continue
        name = str(lum.get("name", ""))
        label = str(labels.get(name, name))
        if lum["type"] == "sky":
            ground = finite(lum.get("ground_reflectance"))
            row = SkyRow(label=label, model=_sky_model(lum), level=_sky_level(lum),
                         ground_reflectance=0.2 if ground is None else ground)
            if lum.get("sun_direction") is not None:
                elevation, bearing = _toward(lum["sun_direction"], north_deg)
                if elevation is not None:
                    row.sun = f"sun {elevation:.1f}° high, {bearing}"
            row.openings = _openings(lum.get("portals"), north_deg)
            row.site = not row.openings
            row.flux_lm = traced_flux.get(name)
            skies.append(row)
        else:
            sun = _sun_row(lum, label, north_deg, sun_position)
            sun.flux_lm = traced_flux.get(name)
            suns.append(sun)
    return skies, suns


# --- sunlight exposure -----------------------------------------------------------------------

@dataclass
class ExposurePoint:
    name: str
    hours: Optional[float]
    level: str  # none, minimum, medium, high
    periods: List[Tuple[str, str]]


@dataclass
class SunlightExposure:
    """EN 17037 sunlight exposure: the date, the least solar altitude, each point's hours."""

    date: str
    min_elevation_deg: Optional[float]
    step_minutes: Optional[float]
    points: List[ExposurePoint]
    site: str = ""


def read_exposure(doc: Dict[str, Any], scene: Dict[str, Any],
                  labels: Dict[str, str]) -> Optional[SunlightExposure]:
    """The results' ``sunlight_exposure`` (docs/scene-format.md, "Sunlight exposure"), None where absent."""
    view = sunlight_view(doc)  # the results reader's one reading of the key
    if view is None:
        return None
    points = [ExposurePoint(labels.get(p.name, p.name), p.hours, p.level, list(p.periods))
              for p in view.points]
    out = SunlightExposure(date=view.date or "–", min_elevation_deg=view.min_elevation_deg,
                           step_minutes=view.step_minutes, points=points)
    spec = scene.get("sunlight_exposure")
    site = spec.get("site") if isinstance(spec, dict) else None
    if isinstance(site, dict):
        lat, lon = finite(site.get("latitude_deg")), finite(site.get("longitude_deg"))
        if lat is not None and lon is not None:
            offset = finite(site.get("utc_offset_h")) or 0.0
            out.site = f"{_site(lat, lon)}, local time UTC{offset:+g} h"
    return out
