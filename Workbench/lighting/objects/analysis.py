# SPDX-License-Identifier: LGPL-2.1-or-later
"""Lighting analysis: a group holding solver settings, export settings and, once run, its
results object (objects/results.py).

It uses the luminaires, targets and placement domains in its group, plus those that belong
to no analysis at all (so a simple model needs no drag and drop)."""
from __future__ import annotations

from typing import Any, Dict, List, Optional

from lighting.objects import luminaire, observer, placement_domain, report_settings, target
from lighting.objects.base import BaseProxy, Prop, READ_ONLY, objects_of_type
from lighting.solver import run as solver_run

TYPE = "Lighting::Analysis"
#: Backend choices while the native module cannot be imported (documents still open then);
#: otherwise they come from the solver's registry (backend_choices).
FALLBACK_BACKENDS = ("auto", "embree", "vulkan")
COLOR_MAPS = ("Rainbow", "Heat", "Grey")
SCALE_MODES = ("Requirements", "Auto", "Fixed")
MESH_STORAGE = ("Auto", "Inline", "PLY")
#: Bookkeeping properties: NoModify, so writing them neither marks the document modified nor
#: lands in a pending undo transaction (a Check must not add an undo step).
BOOKKEEPING = ("Status", "SceneFile")
#: Stage names older versions wrote into Status (and could save that way).
TRANSIENT_STATUS = ("checking", "exporting", "exported", "solving")
_RO = READ_ONLY


class Analysis(BaseProxy):
    """Solver and display settings of one lighting calculation; its group holds the inputs
    it uses and its results object."""

    TYPE = TYPE
    PROPERTIES = {
        # Solver
        "Photons": Prop("App::PropertyInteger", "Solver",
                        "Photon paths to trace (when TargetAccuracy is 0)", 200000),
        "TargetAccuracy": Prop("App::PropertyFloat", "Solver",
                               "Wanted relative half-width of every target's Em confidence "
                               "interval (0.05 = +-5 %); 0 = trace exactly Photons. Tracing stops "
                               "as soon as every target reaches it (within MaxPhotons)", 0.0),
        "MaxPhotons": Prop("App::PropertyInteger", "Solver",
                           "Upper limit on photons when TargetAccuracy is used", 20000000),
        "Confidence": Prop("App::PropertyFloat", "Solver",
                           "Two-sided confidence level of the intervals, in (0, 1)", 0.95),
        "MaxBounces": Prop("App::PropertyInteger", "Solver",
                           "Safety limit on interactions per path (Russian roulette ends paths "
                           "without bias)", 1000),
        "Seed": Prop("App::PropertyInteger", "Solver",
                     "Random seed: same scene + seed + photons give identical results", 1),
        "Backend": Prop("App::PropertyEnumeration", "Solver",
                        "Tracing backend of the native solver: auto (a real GPU when one is "
                        "usable, else the CPU) or one this solver build has", "auto",
                        items=FALLBACK_BACKENDS),
        "Threads": Prop("App::PropertyInteger", "Solver", "Worker threads (0 = all cores)", 0),
        "Live": Prop("App::PropertyBool", "Solver",
                     "GUI: refine the results in the background while the model is edited "
                     "(docs/live.md); scripts use lighting.LiveSession", False),
        "Decide": Prop("App::PropertyBool", "Solver",
                       "When targets have requirements (and TargetAccuracy is 0): trace until "
                       "every requirement is decided pass or fail from its interval, with Photons "
                       "as the budget (undecided ones say what deciding would cost); off: trace "
                       "exactly Photons", True),
        "Contributions": Prop("App::PropertyBool", "Solver",
                              "Trace each control group's contribution separately (luminaires' "
                              "ControlGroup), so light scenes and dimming are shown by rescaling "
                              "one trace; on when the analysis has a light scene", False),
        # Export
        "LinearDeflection": Prop("App::PropertyLength", "Export",
                                 "Tessellation: largest distance between a curved surface and "
                                 "its triangles", 10.0),
        "AngularDeflection": Prop("App::PropertyAngle", "Export",
                                  "Tessellation: largest angle between neighbouring triangles "
                                  "of a curved surface", 28.5),
        "MeshStorage": Prop("App::PropertyEnumeration", "Export",
                            "Inline: triangles in the JSON; PLY: binary files next to it; "
                            "Auto: PLY above 20000 triangles", "Auto", items=MESH_STORAGE),
        "OutputDirectory": Prop("App::PropertyPath", "Export",
                                "Folder for scene.json and results.json; empty = "
                                "'<document>_lighting' next to the saved document"),
        # Display
        "ColorMap": Prop("App::PropertyEnumeration", "Display", "False-colour map",
                         "Rainbow", items=COLOR_MAPS),
        "ScaleMode": Prop("App::PropertyEnumeration", "Display",
                          "Requirements: 0 to 1.5 x the highest required Em, the same for "
                          "every run (Auto without any requirement); Auto: 0 to the largest "
                          "result of this run; Fixed: ScaleMin..ScaleMax",
                          "Requirements", items=SCALE_MODES),
        "ScaleMinLux": Prop("App::PropertyFloat", "Display", "Illuminance at the bottom of the "
                            "scale, lx (Fixed)", 0.0),
        "ScaleMaxLux": Prop("App::PropertyFloat", "Display", "Illuminance at the top of the "
                            "scale, lx (Fixed)", 1000.0),
        "ShowLegend": Prop("App::PropertyBool", "Display", "Draw the colour legend in the 3D view",
                           True),
        "ActiveLightScene": Prop("App::PropertyLink", "Display",
                                 "The light scene the results show (rescaled, no tracing); "
                                 "empty: as traced, every control group at full flux"),
        # Results (read only)
        "Status": Prop("App::PropertyString", "Results",
                       "Outcome of the last run or check: not run, done, partial results "
                       "(cancelled), check failed, failed: ...; whether the results are still "
                       "current: lighting.results_state()", "not run", _RO),
        "SceneFile": Prop("App::PropertyString", "Results", "Last exported scene file", "", _RO),
        # Report: the calculation report's inputs (objects/report_settings.py)
        **report_settings.PROPERTIES,
        # The results themselves live in the results object of the group (objects/results.py).
    }

    @classmethod
    def ensure_properties(cls, obj: Any, set_defaults: bool = False) -> None:
        """The table's properties, then the Backend choices of this solver build. (Made or
        restored, an analysis also needs the observer that deletes its results with it.)"""
        from lighting.objects.results import install_cascade

        install_cascade()
        current = obj.Backend if "Backend" in obj.PropertiesList else None
        super().ensure_properties(obj, set_defaults)
        obj.Backend = backend_choices(current)
        obj.Backend = current or "auto"
        for name in BOOKKEEPING:
            if "NoModify" not in obj.getPropertyStatus(name):
                obj.setPropertyStatus(name, "NoModify")
        # A live session is a GUI state, not part of the file: reopened, Live is off.
        if "Transient" not in obj.getPropertyStatus("Live"):
            obj.setPropertyStatus("Live", "Transient")

    def onChanged(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        """Switching the light scene re-derives what the results object shows."""
        if prop == "ActiveLightScene" and not getattr(obj.Document, "Restoring", False):
            from lighting.objects import light_scene

            light_scene.refresh(obj)

    def onDocumentRestored(self, obj: Any) -> None:  # noqa: N802 (FreeCAD API name)
        """Files of older versions could be saved in the middle of a stage ("checking"):
        restore the state their results are in."""
        super().onDocumentRestored(obj)
        if obj.Status in TRANSIENT_STATUS:
            from lighting.objects.results import data, of_analysis, status_of

            obj.Status = status_of(data(of_analysis(obj)))


def backend_choices(current: Optional[str] = None) -> List[str]:
    """The Backend property's items: the solver's registry (``lightsolver.backends()``, "auto"
    first) when the module can be imported, else FALLBACK_BACKENDS. A document's value that
    this build lacks (saved where Vulkan was built) stays an item, so opening the file does not
    change it; a run then fails with the solver's list of the backends it has."""
    names = solver_run.backend_names() or list(FALLBACK_BACKENDS)
    if current and current not in names:
        names.append(current)
    return names


def _in_some_analysis(obj: Any) -> bool:
    return any(getattr(parent, "Proxy", None) is not None and isinstance(parent.Proxy, Analysis)
               for parent in obj.InList)


def members(analysis: Any, type_name: str) -> List[Any]:
    """Objects of a Lighting type the analysis uses: those in its group, plus those in no
    analysis at all."""
    doc = analysis.Document
    group = set(o.Name for o in analysis.Group)
    return [o for o in objects_of_type(doc, type_name)
            if o.Name in group or not _in_some_analysis(o)]


def luminaires(analysis: Any) -> List[Any]:
    """Luminaires used by the analysis."""
    return members(analysis, luminaire.TYPE)


def targets(analysis: Any) -> List[Any]:
    """Targets used by the analysis."""
    return members(analysis, target.TYPE)


def requirements(analysis: Any) -> Dict[str, Dict[str, float]]:
    """The requirements of the analysis' targets as the document holds them now (their scene
    entries' ``requirements``, objects/target.py), by target name: what the results reader
    judges on the point estimates of targets whose results carry no verdicts of the solver
    (results of older versions, requirements set after the run)."""
    from lighting.objects import daylight_target

    # A daylight-factor grid's requirements are judged by the solver alone (DF, not lux).
    return {t.Name: dict(target.requirements_entry(t).get("requirements", {}))
            for t in targets(analysis) if not daylight_target.is_daylight_factor(t)}


def observers(analysis: Any) -> List[Any]:
    """Observers (eyes for glare) used by the analysis."""
    return members(analysis, observer.TYPE)


def placement_domains(analysis: Any) -> List[Any]:
    """Placement domains used by the analysis."""
    return members(analysis, placement_domain.TYPE)


def find_analysis(doc: Any, name: Optional[str] = None) -> Optional[Any]:
    """The analysis called ``name``, or the document's only/first analysis, or None."""
    found = objects_of_type(doc, TYPE)
    if name is not None:
        found = [o for o in found if o.Name == name or o.Label == name]
    return found[0] if found else None


def settings(analysis: Any) -> Dict[str, Any]:
    """The scene's ``settings`` object (docs/scene-format.md): ``decide`` when the analysis
    decides its targets' requirements (a scene file then reproduces the run in the CLI)."""
    out = {"photons": int(analysis.Photons), "max_bounces": int(analysis.MaxBounces),
           "seed": int(analysis.Seed), "confidence": float(analysis.Confidence)}
    if decides(analysis):
        out["decide"] = True
    if bool(getattr(analysis, "Contributions", False)):
        out["contributions"] = True
    return out


def control_groups(analysis: Any) -> List[str]:
    """The control groups of the luminaires an analysis places, in first-seen order."""
    from lighting.objects import luminaire_layout

    return list(dict.fromkeys(luminaire.control_group(lum)
                              for lum in luminaire_layout.placed_luminaires(analysis)))


def decides(analysis: Any) -> bool:
    """Whether a run traces until the requirements are decided: Decide on, no accuracy goal,
    and some target with a requirement."""
    if not bool(getattr(analysis, "Decide", False)) or float(analysis.TargetAccuracy) > 0.0:
        return False
    from lighting.objects import daylight_target

    return any(float(getattr(t, "RequiredLux", 0.0)) > 0.0
               or (daylight_target.is_daylight_factor(t) and daylight_target.has_requirements(t))
               or (getattr(t, "TargetType", "") == "Grid"
                   and float(getattr(t, "RequiredUniformity", 0.0)) > 0.0)
               for t in targets(analysis))


def check(analysis: Any) -> List[tuple]:
    """Absurd solver and export settings: list of (level, text)."""
    problems: List[tuple] = []
    name = analysis.Label
    if analysis.Photons < 1:
        problems.append(("error", f"Analysis '{name}': Photons must be >= 1"))
    elif analysis.Photons < 10000:
        problems.append(("warning", f"Analysis '{name}': {analysis.Photons} photons give very "
                                    "wide confidence intervals"))
    if not (0.0 < analysis.Confidence < 1.0):
        problems.append(("error", f"Analysis '{name}': Confidence must be in (0, 1) "
                                  f"(got {analysis.Confidence:g})"))
    if analysis.TargetAccuracy < 0.0 or analysis.TargetAccuracy >= 1.0:
        problems.append(("error", f"Analysis '{name}': TargetAccuracy must be in [0, 1) "
                                  f"(got {analysis.TargetAccuracy:g})"))
    elif 0.0 < analysis.TargetAccuracy < 0.002:
        problems.append(("warning", f"Analysis '{name}': TargetAccuracy "
                                    f"{analysis.TargetAccuracy:g} needs a huge photon count"))
    if analysis.TargetAccuracy > 0.0 and analysis.MaxPhotons < analysis.Photons:
        problems.append(("error", f"Analysis '{name}': MaxPhotons must be >= Photons"))
    if analysis.MaxBounces < 1:
        problems.append(("error", f"Analysis '{name}': MaxBounces must be >= 1"))
    if analysis.Seed < 0:
        problems.append(("error", f"Analysis '{name}': Seed must be >= 0"))
    deflection = float(analysis.LinearDeflection)
    if deflection <= 0.0:
        problems.append(("error", f"Analysis '{name}': LinearDeflection must be > 0"))
    elif deflection > 500.0:
        problems.append(("warning", f"Analysis '{name}': LinearDeflection {deflection:g} mm "
                                    "makes curved surfaces very coarse"))
    if not (0.0 < float(analysis.AngularDeflection) <= 90.0):
        problems.append(("error", f"Analysis '{name}': AngularDeflection must be in (0, 90] deg"))
    if analysis.ScaleMode == "Fixed" and analysis.ScaleMaxLux <= analysis.ScaleMinLux:
        problems.append(("warning", f"Analysis '{name}': ScaleMaxLux must exceed ScaleMinLux"))
    return problems
