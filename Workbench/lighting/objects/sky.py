# SPDX-License-Identifier: LGPL-2.1-or-later
"""Sky: daylight through the room's openings (docs/daylight.md, docs/scene-format.md "sky",
"The sun"; docs/workbench-daylight.md).

One Sky object exports the scene's ``sky`` luminaire (and, with ``SunEnabled``, a ``sun``
through the same portals). Its portals are the openings of the Arch windows hosted in walls
(all of them when ``Windows`` is empty) and any faces in ``PortalFaces``
(lighting.export.portals computes them). The site (latitude, longitude, elevation, time zone,
north) comes from an Arch Site in the document when there is one, else from the entered
values. App code: works headless, never imports GUI code."""
from __future__ import annotations

import datetime
import math
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

from lighting.compat import get_property, ifc_type
from lighting.objects.base import HIDDEN, READ_ONLY, BaseProxy, Prop

TYPE = "Lighting::Sky"
#: Glazing defaults stated in the panel and the tool tips: a clear double-glazed unit
#: (tau_v 0.75), DIALux's frame factor for a framed window, EN 17037's cleaning allowance.
DEFAULT_TRANSMITTANCE = 0.75
DEFAULT_PANES = 2
DEFAULT_FRAME_FACTOR = 0.8
DEFAULT_MAINTENANCE_FACTOR = 0.9
#: EN 17037 sunlight exposure: the solver's default minimum solar altitude (11 degrees,
#: kDefaultSunlightMinElevation_deg; docs/daylight.md says where it comes from and that the
#: site's own value from the standard's table belongs here) and its default step (1 min).
DEFAULT_SUNLIGHT_MIN_ALTITUDE = 11.0
DEFAULT_SUNLIGHT_STEP_MINUTES = 1


@dataclass(frozen=True)
class DaylightKind:
    """One daylight luminaire type the workbench offers: its scene ``type`` and what the
    workbench object means by it (Tests/python/test_type_tables.py reads these rows)."""

    scene_type: str
    summary: str


#: The daylight types a Sky object exports (the electric ones are objects/luminaire.py's).
DAYLIGHT_KINDS = (
    DaylightKind("sky", "the Sky object: a sky model through the windows' portals"),
    DaylightKind("sun", "the Sky object's SunEnabled: the sun through the same portals"),
)

#: SkyModel choices -> the scene's ``model``.
MODELS: Dict[str, str] = {"CIE overcast": "cie_overcast", "Uniform": "uniform",
                          "CIE standard general sky": "cie", "Perez": "perez"}
#: CIE standard general sky types with a sun-dependent indicatrix (ISO 15469 Table 1: the
#: gradation-only types 1, 3 and 5 have none).
CIE_TYPES_WITH_SUN = {2, 4} | set(range(6, 16))


class Sky(BaseProxy):
    """A sky model shining through portals (Arch windows, selected faces), optionally with the
    sun through the same portals. Its Shape shows the portals."""

    TYPE = TYPE
    PROPERTIES = {
        "SkyModel": Prop("App::PropertyEnumeration", "Sky",
                         "CIE overcast (traditional, L = Lz(1+2cosZ)/3: daylight factors), "
                         "Uniform, CIE standard general sky (CieType 1-15, sun from the site "
                         "and time), Perez (from diffuse and direct values)",
                         "CIE overcast", items=tuple(MODELS)),
        "CieType": Prop("App::PropertyInteger", "Sky",
                        "CIE standard general sky type 1-15 (ISO 15469): 1 overcast ... 12 "
                        "CIE standard clear ... 15 turbid", 12),
        "DiffuseHorizontalLux": Prop("App::PropertyFloat", "Sky",
                                     "Level: the unobstructed sky's diffuse horizontal "
                                     "illuminance in lx (not Perez)", 10000.0),
        "GroundReflectance": Prop("App::PropertyFloat", "Sky",
                                  "Reflectance of the ground below the horizon (0..1)", 0.2),
        "PerezDiffuseHorizontal": Prop("App::PropertyFloat", "Perez",
                                       "Perez: diffuse horizontal value (> 0), in PerezUnits",
                                       15000.0),
        "PerezDirectNormal": Prop("App::PropertyFloat", "Perez",
                                  "Perez: direct normal value (>= 0), in PerezUnits", 40000.0),
        "PerezUnits": Prop("App::PropertyEnumeration", "Perez",
                           "Units of the Perez values: lx (illuminance) or W/m2 (irradiance)",
                           "lx", items=("lx", "W/m2")),
        "Site": Prop("App::PropertyLink", "Site",
                     "Arch Site giving latitude, longitude, elevation, time zone and north "
                     "(Declination); empty = the document's first Arch Site, else the values "
                     "below"),
        "Latitude": Prop("App::PropertyFloat", "Site",
                         "Latitude in degrees, north positive (without an Arch Site)", 48.85),
        "Longitude": Prop("App::PropertyFloat", "Site",
                          "Longitude in degrees, east positive (without an Arch Site)", 2.35),
        "Elevation": Prop("App::PropertyLength", "Site",
                          "Site elevation above sea level (without an Arch Site)", 35000.0),
        "TimeZone": Prop("App::PropertyFloat", "Site",
                         "Standard time zone, hours from UTC (without an Arch Site)", 1.0),
        "North": Prop("App::PropertyAngle", "Site",
                      "True north from the model's +Y axis, counter-clockwise seen from above "
                      "(without an Arch Site; a Site's Declination)", 0.0),
        "Date": Prop("App::PropertyString", "Site", "Date, YYYY-MM-DD", "2026-03-21"),
        "Time": Prop("App::PropertyString", "Site", "Local standard time, hh:mm", "12:00"),
        "SiteUsed": Prop("App::PropertyString", "Site", "Where the site values come from",
                         "", READ_ONLY),
        "SunEnabled": Prop("App::PropertyBool", "Sun",
                           "Add the sun (direct light) through the same portals", False),
        "DirectNormalLux": Prop("App::PropertyFloat", "Sun",
                                "The sun's direct normal illuminance in lx (clear sky ~ 80 000)",
                                80000.0),
        "SunlightExposure": Prop("App::PropertyBool", "Sunlight",
                                 "EN 17037 sunlight exposure: hours of possible sunlight at a "
                                 "reference point in each window that is a portal", False),
        "SunlightDate": Prop("App::PropertyString", "Sunlight",
                             "Assessment day YYYY-MM-DD (EN 17037: 1 February ... 21 March); "
                             "empty = 21 March of Date's year", ""),
        "SunlightMinAltitude": Prop("App::PropertyFloat", "Sunlight",
                                    "Minimum solar altitude in degrees (the site's value from "
                                    "EN 17037's table; 11 = the solver's default, not a "
                                    "site's)", DEFAULT_SUNLIGHT_MIN_ALTITUDE),
        "SunlightStepMinutes": Prop("App::PropertyInteger", "Sunlight",
                                    "Time step in minutes (1 ... 60, dividing 1440): each "
                                    "period's ends are known to one step",
                                    DEFAULT_SUNLIGHT_STEP_MINUTES),
        "Windows": Prop("App::PropertyLinkList", "Portals",
                        "Arch windows that become portals; empty = every window hosted in a "
                        "wall"),
        "PortalFaces": Prop("App::PropertyLinkSubList", "Portals",
                            "Further planar faces that become portals (skylights, openings)"),
        "PortalCount": Prop("App::PropertyInteger", "Portals", "Portals found", 0, READ_ONLY,
                            output=True),
        "PortalSources": Prop("App::PropertyLinkList", "Portals",
                              "The windows the portals come from (kept by recompute, so the "
                              "drawn portals follow a moved window)", None, HIDDEN),
        "GlazingTransmittance": Prop("App::PropertyFloat", "Glazing",
                                     "Visible transmittance tau_v at normal incidence where a "
                                     "window's glass has no material (default 0.75: clear "
                                     "double glazing)", DEFAULT_TRANSMITTANCE),
        "GlazingPanes": Prop("App::PropertyInteger", "Glazing", "Panes: 1 or 2",
                             DEFAULT_PANES),
        "FrameFactor": Prop("App::PropertyFloat", "Glazing",
                            "Glazed fraction of each opening (0..1]; the frame is left out of "
                            "the scene, this factor stands for it", DEFAULT_FRAME_FACTOR),
        "GlazingMaintenanceFactor": Prop("App::PropertyFloat", "Glazing",
                                         "Dirt on the glass (0..1], EN 17037 / CIE 97",
                                         DEFAULT_MAINTENANCE_FACTOR),
        "UseWindowGlass": Prop("App::PropertyBool", "Glazing",
                               "Take tau_v from a window's glass material when it gives a "
                               "Transmittance", True),
    }

    def execute(self, obj: Any) -> None:
        """Show the portals (parallelograms with a short inward arrow)."""
        import Part

        from lighting.export import portals as portals_mod

        found = portals_mod.find_portals(obj)
        shapes = [portals_mod.portal_shape(p) for p in found.portals]
        obj.Shape = Part.makeCompound(shapes) if shapes else Part.Shape()
        if obj.PortalCount != len(found.portals):
            obj.PortalCount = len(found.portals)
        if [w.Name for w in obj.PortalSources] != [w.Name for w in found.windows]:
            obj.PortalSources = list(found.windows)
        site = resolve_site(obj)
        if obj.SiteUsed != site.source:
            obj.SiteUsed = site.source


def skies(doc: Any) -> List[Any]:
    """The document's Sky objects."""
    from lighting.objects.base import objects_of_type

    return objects_of_type(doc, TYPE)


# -- site ------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Site:
    """Latitude and longitude (degrees), elevation (m), time zone (h), north (degrees from +Y,
    counter-clockwise seen from above: the scene's ``metadata.north_deg``)."""

    latitude_deg: float
    longitude_deg: float
    elevation_m: float
    utc_offset_h: float
    north_deg: float
    source: str


def arch_site(obj: Any) -> Optional[Any]:
    """The Sky's Site, or the document's first Arch Site (None without one)."""
    linked = getattr(obj, "Site", None)
    if linked is not None:
        return linked
    for other in obj.Document.Objects:
        proxy_type = getattr(getattr(other, "Proxy", None), "Type", None)
        if proxy_type == "Site" or ifc_type(other) == "site":
            return other
    return None


def resolve_site(obj: Any) -> Site:
    """The site the Sky uses. An Arch Site's Declination is the angle from the document's +Y
    to true north, counter-clockwise seen from above (FreeCAD rotates its solar diagram by
    +Declination and its "true north" view by -Declination), the same sense as
    ``metadata.north_deg``."""
    site = arch_site(obj)
    if site is not None:
        declination = get_property(site, "Declination", 0.0)
        elevation = get_property(site, "Elevation", 0.0)
        return Site(float(get_property(site, "Latitude", 0.0)),
                    float(get_property(site, "Longitude", 0.0)),
                    _value(elevation) / 1000.0, float(get_property(site, "TimeZone", 0)),
                    _value(declination), f"Arch Site '{site.Label}'")
    return Site(float(obj.Latitude), float(obj.Longitude), float(obj.Elevation) / 1000.0,
                float(obj.TimeZone), float(obj.North), "entered values")


def _value(quantity: Any) -> float:
    return float(getattr(quantity, "Value", quantity))


def local_time_iso(obj: Any, site: Site) -> str:
    """``YYYY-MM-DDThh:mm±hh:mm``: the Sky's date and time in the site's zone (ValueError
    naming the property when malformed)."""
    try:
        day = datetime.date.fromisoformat(str(obj.Date).strip())
    except ValueError:
        raise ValueError(f"Sky '{obj.Label}': Date must be YYYY-MM-DD, got {obj.Date!r}") from None
    try:
        clock = datetime.time.fromisoformat(str(obj.Time).strip())
    except ValueError:
        raise ValueError(f"Sky '{obj.Label}': Time must be hh:mm, got {obj.Time!r}") from None
    if not (-14.0 <= site.utc_offset_h <= 14.0):
        raise ValueError(f"Sky '{obj.Label}': time zone {site.utc_offset_h:g} h is beyond "
                         "UTC -14 ... +14")
    minutes = int(round(abs(site.utc_offset_h) * 60.0))
    sign = "-" if site.utc_offset_h < 0 else "+"
    return (f"{day.isoformat()}T{clock.strftime('%H:%M')}"
            f"{sign}{minutes // 60:02d}:{minutes % 60:02d}")


def sun_direction(obj: Any, site: Site) -> Tuple[List[float], float]:
    """(direction toward the sun in the scene's frame, elevation in degrees) from the solver's
    sun position (NREL SPA via libnova, docs/daylight.md)."""
    from lighting.solver import run

    ok, reason = run.solver_available()
    if not ok:
        raise ValueError(f"Sky '{obj.Label}': the sun's position needs the solver ({reason})")
    import lightsolver

    sun = lightsolver.sun_position(site.latitude_deg, site.longitude_deg,
                                   local_time_iso(obj, site), elevation_m=site.elevation_m,
                                   north_deg=site.north_deg)
    return [float(c) for c in sun["direction"]], float(sun["elevation_deg"])


def needs_sun(obj: Any) -> bool:
    """Whether the sky model needs the sun's position."""
    model = MODELS[obj.SkyModel]
    return model == "perez" or (model == "cie" and int(obj.CieType) in CIE_TYPES_WITH_SUN)


def glazing(obj: Any, transmittance: Optional[float] = None) -> Dict[str, Any]:
    """A portal's ``glazing`` object: the window's tau_v when given, else the Sky's."""
    tau = float(obj.GlazingTransmittance) if transmittance is None else float(transmittance)
    return {"transmittance": tau, "panes": int(obj.GlazingPanes),
            "frame_factor": float(obj.FrameFactor),
            "maintenance_factor": float(obj.GlazingMaintenanceFactor)}


def sky_entry(obj: Any, portals: List[Dict[str, Any]], site: Site) -> Dict[str, Any]:
    """The ``sky`` luminaire (docs/scene-format.md): its own group, so daylight-factor grids
    count only its light (docs/scene-format.md, "Targets")."""
    model = MODELS[obj.SkyModel]
    entry: Dict[str, Any] = {"name": obj.Name, "type": "sky", "group": obj.Name, "model": model}
    if model == "cie":
        entry["cie_type"] = int(obj.CieType)
    if model == "perez":
        day = datetime.date.fromisoformat(local_time_iso(obj, site)[:10])
        entry["perez"] = {"diffuse_horizontal": float(obj.PerezDiffuseHorizontal),
                          "direct_normal": float(obj.PerezDirectNormal),
                          "units": str(obj.PerezUnits),
                          "day_of_year": day.timetuple().tm_yday}
    else:
        entry["diffuse_horizontal_lx"] = float(obj.DiffuseHorizontalLux)
    if needs_sun(obj):
        direction, elevation = sun_direction(obj, site)
        if elevation < 0.0:
            raise ValueError(f"Sky '{obj.Label}': the sun is below the horizon at "
                             f"{local_time_iso(obj, site)} ({elevation:.1f}°); this sky model "
                             "needs it up: change Date/Time or take CIE overcast")
        entry["sun_direction"] = [round(c, 12) for c in direction]
    entry["ground_reflectance"] = float(obj.GroundReflectance)
    if bool(obj.SunEnabled) and model != "perez":
        entry["sun_direct_normal_lx"] = float(obj.DirectNormalLux)
    entry["portals"] = portals
    return entry


def sun_entry(obj: Any, portals: List[Dict[str, Any]], site: Site) -> Dict[str, Any]:
    """The ``sun`` through the sky's portals (docs/scene-format.md, "The sun"), in a group of its own."""
    return {"name": f"{obj.Name}_sun", "type": "sun", "group": f"{obj.Name}_sun",
            "illuminance_lx": float(obj.DirectNormalLux),
            "site": {"latitude_deg": site.latitude_deg, "longitude_deg": site.longitude_deg,
                     "elevation_m": site.elevation_m},
            "time": local_time_iso(obj, site), "north_deg": site.north_deg,
            "portals": portals}


def check(obj: Any) -> List[tuple]:
    """Checks only the document can make (the solver checks the scene's values)."""
    problems: List[tuple] = []
    name = obj.Label
    for prop in ("FrameFactor", "GlazingMaintenanceFactor", "GlazingTransmittance"):
        value = float(getattr(obj, prop))
        if not (0.0 < value <= 1.0) or not math.isfinite(value):
            problems.append(("error", f"Sky '{name}': {prop} must be more than 0 and at most 1 "
                                      f"(got {value:g})"))
    if int(obj.GlazingPanes) not in (1, 2):
        problems.append(("error", f"Sky '{name}': GlazingPanes must be 1 or 2"))
    if obj.SkyModel == "CIE standard general sky" and not 1 <= int(obj.CieType) <= 15:
        problems.append(("error", f"Sky '{name}': CieType must be 1 ... 15"))
    return problems
