# SPDX-License-Identifier: LGPL-2.1-or-later
"""The calculation report's inputs, kept on the analysis (group "Report"): who the report is
for and who signs it, which date it carries, and the inputs of its energy estimate (LENI,
EN 15193-1). They are saved with the document, edited in the Report command's panel
(taskpanels/report_panel.py) or the property editor, and reach the report through
``lighting.report`` (reporting.py): the sign-off block, the cover and the LENI table.

They are not part of the lighting model: the scene export ignores them and changing them
leaves the results current (export/fingerprint.py reads only the Solver settings). The report
receives them as the scene's ``metadata.report`` (docs/report.md) when it is written, so a
report written again after an edit shows the new names without a new run.

App code: no GUI imports."""
from __future__ import annotations

import datetime
import math
from typing import Any, Dict, List, Optional, Tuple

from lighting.messages import LightingError
from lighting.objects.base import Prop

GROUP = "Report"
#: ReportDate: the day the report is written, the day the results were calculated, FixedDate.
DATE_POLICIES = ("Today", "Calculation", "Fixed")
#: EN 15193-1 Annex F's office defaults (t_D, t_N), a starting point the user replaces.
OFFICE_HOURS = (2250.0, 250.0)
YEAR_HOURS = 8760.0

PROPERTIES = {
    "ProjectName": Prop("App::PropertyString", GROUP,
                        "Project name: the report's title and the sign-off block's project; "
                        "empty = the document's label", output=True),
    "ProjectNumber": Prop("App::PropertyString", GROUP,
                          "Project number, printed under the title on the report's cover",
                          output=True),
    "Client": Prop("App::PropertyString", GROUP,
                   "The client, printed under the title on the report's cover", output=True),
    "PreparedBy": Prop("App::PropertyString", GROUP,
                       "Who prepared the report (sign-off block); empty = the document's "
                       "CreatedBy and Company (File > Document properties)", output=True),
    "CheckedBy": Prop("App::PropertyString", GROUP,
                      "Who checked the report (sign-off block); empty = a blank line to sign",
                      output=True),
    "ReportDate": Prop("App::PropertyEnumeration", GROUP,
                       "Date printed on the report: Today (the day it is written), Calculation "
                       "(the day the results were calculated) or Fixed (FixedDate)", "Today",
                       items=DATE_POLICIES, output=True),
    "FixedDate": Prop("App::PropertyString", GROUP,
                      "The report's date when ReportDate is Fixed, YYYY-MM-DD", output=True),
    "EnergyEstimate": Prop("App::PropertyBool", GROUP,
                           "Print the lighting energy estimate LENI (EN 15193-1, simplified "
                           "method) from the operating hours and control factors below", False,
                           output=True),
    "OperatingHoursDay": Prop("App::PropertyFloat", GROUP,
                              "Annual operating hours with daylight t_D, h/a (EN 15193-1; "
                              "office: 2250)", OFFICE_HOURS[0], output=True),
    "OperatingHoursNight": Prop("App::PropertyFloat", GROUP,
                                "Annual operating hours without daylight t_N, h/a (EN 15193-1; "
                                "office: 250)", OFFICE_HOURS[1], output=True),
    "OccupancyFactor": Prop("App::PropertyFloat", GROUP,
                            "Occupancy dependency factor F_O, 0..1 (1 = no presence control)",
                            1.0, output=True),
    "DaylightDependencyFactor": Prop("App::PropertyFloat", GROUP,
                                     "Daylight dependency factor F_D, 0..1 (1 = no daylight "
                                     "control)", 1.0, output=True),
    "ConstantIlluminanceFactor": Prop("App::PropertyFloat", GROUP,
                                      "Constant illuminance factor F_C, 0..1 (1 = no constant "
                                      "illuminance control)", 1.0, output=True),
    "ParasiticEnergy": Prop("App::PropertyFloat", GROUP,
                            "Parasitic energy (controls standby, emergency lighting charging), "
                            "kWh/(m2 a)", 0.0, output=True),
    "EnergyFloorArea": Prop("App::PropertyFloat", GROUP,
                            "Floor area LENI is given per, m2; 0 = the largest upward-facing "
                            "calculation grid's area", 0.0, output=True),
    "ReportFile": Prop("App::PropertyString", GROUP,
                       "The file the report was last written to (.pdf or .html); the Report "
                       "command proposes it again", output=True),
}

#: Energy property -> the report's ``metadata.report.energy`` key (docs/report.md).
ENERGY_KEYS: Tuple[Tuple[str, str], ...] = (
    ("OperatingHoursDay", "daylight_hours"), ("OperatingHoursNight", "night_hours"),
    ("ConstantIlluminanceFactor", "constant_illuminance_factor"),
    ("OccupancyFactor", "occupancy_factor"),
    ("DaylightDependencyFactor", "daylight_dependency_factor"),
    ("ParasiticEnergy", "parasitic_kwh_m2"))
FACTORS = ("OccupancyFactor", "DaylightDependencyFactor", "ConstantIlluminanceFactor")


def _text(analysis: Any, name: str) -> str:
    return str(getattr(analysis, name, "") or "").strip()


def signoff(analysis: Any) -> Dict[str, str]:
    """The sign-off fields the analysis names (project, author, checked_by, project_number,
    client); empty ones left out, so that the document's own (its label, CreatedBy) stand in
    for them."""
    fields = {"project": _text(analysis, "ProjectName"), "author": _text(analysis, "PreparedBy"),
              "checked_by": _text(analysis, "CheckedBy"),
              "project_number": _text(analysis, "ProjectNumber"),
              "client": _text(analysis, "Client")}
    return {key: value for key, value in fields.items() if value}


def problems(analysis: Any) -> List[str]:
    """What keeps the report inputs from being used, by property name ([] when fine)."""
    found = []
    if getattr(analysis, "ReportDate", "Today") == "Fixed":
        try:
            datetime.date.fromisoformat(_text(analysis, "FixedDate"))
        except ValueError:
            found.append(f"FixedDate: a date YYYY-MM-DD is needed when ReportDate is Fixed "
                         f"(got {_text(analysis, 'FixedDate')!r})")
    if not bool(getattr(analysis, "EnergyEstimate", False)):
        return found
    values = {name: float(getattr(analysis, name, 0.0)) for name, _ in ENERGY_KEYS}
    values["EnergyFloorArea"] = float(getattr(analysis, "EnergyFloorArea", 0.0))
    for name, value in values.items():
        if not math.isfinite(value) or value < 0.0:
            found.append(f"{name}: must be a number >= 0 (got {value:g})")
    for name in FACTORS:
        if values[name] > 1.0:
            found.append(f"{name}: a control factor lies in 0..1 (got {values[name]:g})")
    hours = values["OperatingHoursDay"] + values["OperatingHoursNight"]
    if math.isfinite(hours) and hours > YEAR_HOURS:
        found.append(f"OperatingHoursDay + OperatingHoursNight: {hours:g} h exceed the "
                     f"{YEAR_HOURS:g} hours of a year")
    return found


def energy(analysis: Any) -> Optional[Dict[str, float]]:
    """The report's ``metadata.report.energy`` block (None when EnergyEstimate is off);
    LightingError naming the property for a value LENI cannot use."""
    if not bool(getattr(analysis, "EnergyEstimate", False)):
        return None
    wrong = problems(analysis)
    if wrong:
        raise LightingError(f"Analysis '{analysis.Label}': report inputs: " + "; ".join(wrong))
    block = {key: float(getattr(analysis, name)) for name, key in ENERGY_KEYS}
    area = float(getattr(analysis, "EnergyFloorArea", 0.0))
    if area > 0.0:
        block["area_m2"] = area
    return block


def metadata(analysis: Any) -> Dict[str, Any]:
    """What the report inputs add to the scene's ``metadata`` for the report: ``report``
    ({project, author, checked_by, project_number, client, energy}: the names given, the
    energy block). LightingError for unusable inputs."""
    block: Dict[str, Any] = dict(signoff(analysis))
    found = energy(analysis)
    if found is not None:
        block["energy"] = found
    return {"report": block}


def report_date(analysis: Any, finished_utc: Optional[str] = None) -> Optional[str]:
    """The date the report carries by ``ReportDate``: None (today: the generator's default),
    the day the results were calculated (``finished_utc`` of their provenance, ISO time; None
    when they do not say), or FixedDate. LightingError for a FixedDate that is no date."""
    policy = getattr(analysis, "ReportDate", "Today")
    if policy == "Fixed":
        wrong = [p for p in problems(analysis) if p.startswith("FixedDate")]
        if wrong:
            raise LightingError(f"Analysis '{analysis.Label}': report inputs: {wrong[0]}")
        return _text(analysis, "FixedDate")
    if policy == "Calculation" and finished_utc:
        try:
            return datetime.datetime.fromisoformat(
                finished_utc.replace("Z", "+00:00")).date().isoformat()
        except ValueError:
            return None
    return None


def values(analysis: Any) -> Dict[str, Any]:
    """Every report input of ``analysis`` by property name (the panel's fields)."""
    return {name: getattr(analysis, name) for name in PROPERTIES if hasattr(analysis, name)}


def apply(analysis: Any, changed: Dict[str, Any]) -> List[str]:
    """Write ``changed`` (property name -> value) to the analysis in one undo step "Report
    settings"; only values that differ are written (none: no undo step, the document stays
    unmodified). Returns the names written."""
    differing = {name: value for name, value in changed.items()
                 if name in PROPERTIES and getattr(analysis, name) != value}
    if not differing:
        return []
    doc = analysis.Document
    doc.openTransaction("Report settings")
    try:
        for name, value in differing.items():
            setattr(analysis, name, value)
    finally:
        doc.commitTransaction()
    return sorted(differing)
