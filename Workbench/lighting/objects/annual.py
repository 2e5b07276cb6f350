# SPDX-License-Identifier: LGPL-2.1-or-later
"""Annual daylight: a year of daylight in the analysis' rooms (docs/daylight.md, "A year of
daylight"; docs/workbench-daylight.md, "Annual daylight").

An object of its own in the analysis, beside the Sky, rather than more properties on the Sky:
the Sky describes one moment (its model, date and time: the daylight factor, a point-in-time
check), the annual analysis asks another question over the whole year, with inputs of its own
(the weather file, the sky's subdivision, photons, blinds) and results of its own (sDA, ASE,
UDI, EN 17037 per grid). It takes the Sky's portals and site (north) and the analysis' grids.

Its results are kept on it as the solver gave them: ``SummaryJson`` holds the run's
``lightsolver.annual/1`` summary (read through ``lightsolver_results.read_annual``, never by
hand), with the weather file's name and sha256 and the fingerprint of the model it traced;
``SummaryLines`` (the panel's lines) is derived from it, not saved. App code: works headless,
never imports GUI code."""
from __future__ import annotations

import json
from typing import Any, Dict, List, Optional

from lighting.objects.base import HIDDEN, READ_ONLY, BaseProxy, Prop, objects_of_type

TYPE = "Lighting::AnnualDaylight"
#: Sky subdivisions offered (Reinhart MF -> patches, ground included: docs/daylight.md).
SUBDIVISIONS = {"1 (146 patches)": 1, "2 (578 patches)": 2, "4 (2306 patches)": 4}
#: What the grids show (viewproviders/annual_coloring.py); "Run illuminance" = the analysis'
#: own run, as without an annual analysis.
MAPS = ("DA300", "UDI 100-2000 lx", "ASE hours", "sDA verdict", "Run illuminance")
DEFAULT_PHOTONS = 20_000_000
_RO = READ_ONLY


class AnnualDaylight(BaseProxy):
    """A year of daylight through the Sky's portals on the analysis' grids (module doc)."""

    TYPE = TYPE
    PROPERTIES = {
        "WeatherFile": Prop("App::PropertyFile", "Annual",
                            "EnergyPlus weather file (.epw) of the site: hourly direct and "
                            "diffuse light for the year"),
        "SkySubdivision": Prop("App::PropertyEnumeration", "Annual",
                               "Reinhart subdivision of the sky into patches (MF 1 = "
                               "Tregenza's 145 + ground; finer: sharper sky, more photons)",
                               "1 (146 patches)", items=tuple(SUBDIVISIONS)),
        "Photons": Prop("App::PropertyInteger", "Annual",
                        "Photon paths traced for the whole year (one trace for every sky "
                        "patch and sun position)", DEFAULT_PHOTONS),
        "Seed": Prop("App::PropertyInteger", "Annual", "Random seed (same seed, same result)",
                     1),
        "Confidence": Prop("App::PropertyFloat", "Annual",
                           "Confidence level of the intervals and verdicts (0..1)", 0.95),
        "BlindsTransmittance": Prop("App::PropertyFloat", "Annual",
                                    "IES LM-83 blinds rule: the blinds' transmittance when "
                                    "closed (an occupied hour with direct sun on more than 2 % "
                                    "of the area uses it); 0 = no blinds", 0.0),
        "GroundReflectance": Prop("App::PropertyFloat", "Annual",
                                  "Ground reflectance; negative = the Sky's", -1.0),
        "Map": Prop("App::PropertyEnumeration", "Display",
                    "What the grids show: DA300 (fraction of occupied hours >= 300 lx), UDI "
                    "100-2000 lx (fraction of occupied hours), ASE hours (occupied hours of "
                    "direct sun > 1000 lx), sDA verdict per cell (DA300 >= 50 %: pass, fail, "
                    "undecided), or the analysis' own run", "DA300", items=MAPS),
        "Status": Prop("App::PropertyString", "Results",
                       "not run, done, check failed, failed: ...", "not run", _RO),
        "WeatherName": Prop("App::PropertyString", "Results",
                            "The weather file the results were computed from", "", _RO),
        "WeatherSha256": Prop("App::PropertyString", "Results",
                              "SHA-256 of that weather file", "", _RO),
        "NorthUsed": Prop("App::PropertyFloat", "Results",
                          "North (degrees from +Y, counter-clockwise) the run took from the "
                          "Sky's site", 0.0, _RO),
        "OutputFolder": Prop("App::PropertyString", "Results",
                             "Folder of the run's scene, annual.json and annual.npz (hourly "
                             "values)", "", _RO),
        "SummaryJson": Prop("App::PropertyString", "Results",
                            "The run's summary (lightsolver.annual/1 JSON)", "", HIDDEN),
        "InputsFingerprint": Prop("App::PropertyString", "Results",
                                  "Fingerprint of the model the run exported", "", HIDDEN),
        "SummaryLines": Prop("App::PropertyStringList", "Results",
                             "The results in words (derived from SummaryJson)", None, _RO),
    }

    @classmethod
    def ensure_properties(cls, obj: Any, set_defaults: bool = False) -> None:
        """The table's properties; SummaryLines transient (derived from SummaryJson)."""
        super().ensure_properties(obj, set_defaults)
        if "Transient" not in obj.getPropertyStatus("SummaryLines"):
            obj.setPropertyStatus("SummaryLines", "Transient")

    def onChanged(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        if prop == "SummaryJson" and "SummaryLines" in obj.PropertiesList:
            if not getattr(obj.Document, "Restoring", False):
                derive(obj)

    def onDocumentRestored(self, obj: Any) -> None:  # noqa: N802 (FreeCAD API name)
        super().onDocumentRestored(obj)
        derive(obj)


def derive(obj: Any) -> None:
    """SummaryLines from SummaryJson (empty without results or with unreadable ones)."""
    from lighting import annual_results

    labels = {}
    analysis = analysis_of(obj)
    if analysis is not None:
        from lighting.objects import analysis as analysis_mod

        labels = {t.Name: t.Label for t in analysis_mod.targets(analysis)}
    lines = annual_results.summary_lines(summary(obj), labels)
    if list(obj.SummaryLines) != lines:
        obj.SummaryLines = lines


def summary(obj: Optional[Any]) -> Optional[Dict[str, Any]]:
    """The stored summary (the parsed JSON), or None."""
    if obj is None or not getattr(obj, "SummaryJson", ""):
        return None
    try:
        parsed = json.loads(obj.SummaryJson)
    except ValueError:
        return None
    return parsed if isinstance(parsed, dict) else None


def mf(obj: Any) -> int:
    """The Reinhart subdivision MF of the SkySubdivision choice."""
    return SUBDIVISIONS[str(obj.SkySubdivision)]


def make_annual_daylight(analysis: Any, weather_file: str = "", photons: int = DEFAULT_PHOTONS,
                         name: str = "AnnualDaylight") -> Any:
    """Create an annual daylight analysis in ``analysis`` (module doc): ``weather_file`` an EPW
    file; the analysis needs a Sky (its portals and site) and grid targets."""
    obj = analysis.Document.addObject("App::FeaturePython", name)
    AnnualDaylight(obj)
    obj.Label = "Annual daylight"
    obj.WeatherFile = str(weather_file)
    obj.Photons = int(photons)
    analysis.addObject(obj)
    return obj


def of_analysis(analysis: Any) -> List[Any]:
    """The annual daylight objects in an analysis' group."""
    return [m for m in getattr(analysis, "Group", []) if getattr(getattr(m, "Proxy", None),
                                                                 "Type", "") == TYPE]


def analysis_of(obj: Any) -> Optional[Any]:
    """The analysis whose group holds ``obj``, or None."""
    for parent in obj.InList:
        if getattr(getattr(parent, "Proxy", None), "Type", "") == "Lighting::Analysis":
            return parent
    return None


def all_in(doc: Any) -> List[Any]:
    """Every annual daylight object of a document."""
    return objects_of_type(doc, TYPE)


def check(obj: Any) -> List[tuple]:
    """(level, text) problems only the document can see (the solver checks the rest)."""
    import os

    problems: List[tuple] = []
    name = obj.Label
    path = str(obj.WeatherFile)
    if not path:
        problems.append(("error", f"{name}: no weather file: set WeatherFile to the site's "
                                  ".epw file"))
    elif not os.path.isfile(path):
        problems.append(("error", f"{name}: the weather file '{path}' does not exist"))
    if int(obj.Photons) <= 0:
        problems.append(("error", f"{name}: Photons must be more than 0"))
    if not 0.0 < float(obj.Confidence) < 1.0:
        problems.append(("error", f"{name}: Confidence must be between 0 and 1"))
    blinds = float(obj.BlindsTransmittance)
    if not 0.0 <= blinds <= 1.0:
        problems.append(("error", f"{name}: BlindsTransmittance must be 0 (no blinds) ... 1"))
    if float(obj.GroundReflectance) > 1.0:
        problems.append(("error", f"{name}: GroundReflectance must be at most 1"))
    return problems
