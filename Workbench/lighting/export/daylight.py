# SPDX-License-Identifier: LGPL-2.1-or-later
"""The daylight part of an analysis' scene: its Sky's ``sky`` (and ``sun``) luminaires with
their portals, the windows the portals replace and the site's north
(``metadata.north_deg``). export/scene.py calls :func:`build`."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Set

from lighting.export import portals as portals_mod
from lighting.export import sunlight as sunlight_mod
from lighting.messages import Report
from lighting.objects import sky as sky_mod


@dataclass
class Daylight:
    """What the Sky objects add to a scene."""

    luminaires: List[Dict[str, Any]] = field(default_factory=list)
    replaced_windows: Set[str] = field(default_factory=set)
    north_deg: Optional[float] = None
    labels: Dict[str, str] = field(default_factory=dict)
    #: The scene's top-level ``sunlight_exposure`` (None: not asked).
    sunlight: Optional[Dict[str, Any]] = None


def skies(analysis: Any) -> List[Any]:
    """The Sky objects an analysis uses (in its group, or in no analysis)."""
    from lighting.objects import analysis as analysis_mod

    return analysis_mod.members(analysis, sky_mod.TYPE)


def build(analysis: Any, report: Report) -> Daylight:
    """The daylight luminaires of ``analysis``; problems go to ``report`` (errors name the
    Sky). A scene may hold one sky (a daylight-factor grid needs exactly one)."""
    out = Daylight()
    found_skies = skies(analysis)
    _check_daylight_grids(analysis, found_skies, report)
    if len(found_skies) > 1:
        report.add("error", "More than one Sky in the analysis: keep one (a daylight factor "
                            "is relative to one sky)", found_skies[1].Name)
        found_skies = found_skies[:1]
    for sky in found_skies:
        report.extend(sky_mod.check(sky), sky.Name)
        found = portals_mod.find_portals(sky)
        for level, text in found.problems:
            report.add(level, text, sky.Name)
        if not found.portals:
            report.add("error", f"Sky '{sky.Label}' has no portals: host an Arch window in a "
                                "wall, or add faces to its PortalFaces", sky.Name)
            continue
        for window in found.windows:
            out.replaced_windows.add(window.Name)
            report.add("info", f"'{window.Label}' is a portal of sky '{sky.Label}': its glass "
                               "and frame are left out of the scene (the portal's glazing "
                               "stands for them)", window.Name)
        site = sky_mod.resolve_site(sky)
        entries = [p.scene_entry(sky_mod.glazing(
            sky, p.transmittance if bool(sky.UseWindowGlass) else None)) for p in found.portals]
        try:
            out.luminaires.append(sky_mod.sky_entry(sky, entries, site))
            out.labels[sky.Name] = sky.Label
            if bool(sky.SunEnabled):
                out.luminaires.append(sky_mod.sun_entry(sky, entries, site))
                out.labels[f"{sky.Name}_sun"] = f"{sky.Label} (sun)"
        except ValueError as exc:
            report.add("error", str(exc), sky.Name)
            continue
        out.north_deg = site.north_deg
        if bool(getattr(sky, "SunlightExposure", False)):
            try:
                out.sunlight, problems = sunlight_mod.exposure(sky, found, site)
            except ValueError as exc:
                report.add("error", str(exc), sky.Name)
                continue
            for level, text in problems:
                report.add(level, text, sky.Name)
    return out


def _check_daylight_grids(analysis: Any, found_skies: List[Any], report: Report) -> None:
    """A daylight-factor grid is relative to the analysis' sky: without one it means nothing."""
    from lighting.objects import analysis as analysis_mod
    from lighting.objects import daylight_target

    if found_skies:
        return
    for tgt in analysis_mod.targets(analysis):
        if daylight_target.is_daylight_factor(tgt):
            report.add("error", f"Target '{tgt.Label}' reports daylight factors but the analysis "
                                "has no Sky: add one (Lighting > Sky) or set its Quantity to "
                                "Illuminance", tgt.Name)


def summary_lines(sky: Any) -> List[str]:
    """What the Sky exports, in the user's words (its panel shows them): the sky and its level,
    the site and where it comes from, the sun, each portal with its glazing and the defaults
    the glazing takes."""
    from lighting.objects import sky as sky_mod

    site = sky_mod.resolve_site(sky)
    lines = [f"Sky: {sky.SkyModel}" + (f" type {int(sky.CieType)}"
                                        if sky.SkyModel == "CIE standard general sky" else "")
             + ("" if sky.SkyModel == "Perez"
                else f", {float(sky.DiffuseHorizontalLux):.0f} lx diffuse horizontal")
             + f", ground reflectance {float(sky.GroundReflectance):g}",
             f"Site ({site.source}): {site.latitude_deg:.4f}°, {site.longitude_deg:.4f}° "
             f"(east +), {site.elevation_m:g} m, UTC{site.utc_offset_h:+g} h, north "
             f"{site.north_deg:g}° from +Y; {sky.Date} {sky.Time}"]
    if bool(sky.SunEnabled):
        lines.append(f"Sun: {float(sky.DirectNormalLux):.0f} lx direct normal, through the "
                     "same portals")
    if bool(getattr(sky, "SunlightExposure", False)):
        day = str(sky.SunlightDate).strip() or "21 March"
        lines.append(f"Sunlight exposure (EN 17037): {day}, sun above "
                     f"{float(sky.SunlightMinAltitude):g}°, {int(sky.SunlightStepMinutes)} min "
                     "steps; a reference point in each window")
    found = portals_mod.find_portals(sky)
    for portal in found.portals:
        width, height = portal.edge1.Length / 1000.0, portal.edge2.Length / 1000.0
        use = portal.transmittance if bool(sky.UseWindowGlass) else None
        glass = (f"tau_v {use:g} from the window's glass" if use is not None
                 else f"tau_v {float(sky.GlazingTransmittance):g}")
        lines.append(f"Portal '{portal.label}': {width:.2f} x {height:.2f} m on the wall's "
                     f"inner face, {glass}")
    lines += [text for _, text in found.problems]
    lines.append(f"Glazing: {int(sky.GlazingPanes)} pane(s), frame factor "
                 f"{float(sky.FrameFactor):g}, maintenance factor "
                 f"{float(sky.GlazingMaintenanceFactor):g}; without a glass material tau_v "
                 f"{float(sky.GlazingTransmittance):g} (default: double glazing 0.75, frame "
                 f"{sky_mod.DEFAULT_FRAME_FACTOR:g}, maintenance "
                 f"{sky_mod.DEFAULT_MAINTENANCE_FACTOR:g}). The windows' own glass and frames "
                 "are left out of the scene: the glazing stands for them")
    return lines
