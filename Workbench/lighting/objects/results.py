# SPDX-License-Identifier: LGPL-2.1-or-later
"""Results object: one per analysis, in its group (FEM's result-object pattern).

It holds the one copy of the solver's results document (``ResultsJson``, the
``lightsolver.results/1`` layout of docs/schemas/results.schema.json) and the files of the run.
Everything else on it is derived from that JSON when it is set and when the document is
restored, and is *not* saved (transient): per-target Em and its interval, Emin/Emax/U0, the
grid cells of every target concatenated, and the run facts. Input objects (targets,
luminaires, the analysis' settings) never carry results.

``InputsFingerprint`` records what the run exported (export/fingerprint.py), so whether the
results still describe the model is computed, not remembered: ``solver.store.results_state``
compares it with the model now (after any edit, undo, save and reopen, in scripts and the
GUI alike)."""
from __future__ import annotations

import json
from typing import Any, Dict, List, Optional, Tuple

from lighting.objects.base import BaseProxy, HIDDEN, Prop, READ_ONLY, proxy_type

TYPE = "Lighting::Results"
_RO = READ_ONLY

#: Per-target float lists derived from the JSON (property -> the reader's statistic and part:
#: lightsolver_results.Target's ``em``, ``emin``, ``emax``, ``u0``).
PER_TARGET = {"MeanLux": ("em", "value"), "CiLowLux": ("em", "low"),
              "CiHighLux": ("em", "high"), "MinLux": ("emin", "value"),
              "MaxLux": ("emax", "value"), "Uniformity": ("u0", "value")}
#: Grid cell values, all targets concatenated (property -> lightsolver_results.Cells list).
CELL_VALUES = {"CellsLux": "lux", "CellsCiLowLux": "ci_low_lux",
               "CellsCiHighLux": "ci_high_lux"}


def _derived() -> Dict[str, Prop]:
    props = {
        "TargetNames": Prop("App::PropertyStringList", "Results",
                            "Object names of the targets, in the order of the lists below",
                            None, _RO),
        "CellCounts": Prop("App::PropertyIntegerList", "Results",
                           "Grid cells of each target (0 for face targets)", None, HIDDEN),
        "Photons": Prop("App::PropertyFloat", "Results", "Photon paths traced", 0.0, _RO),
        "Seconds": Prop("App::PropertyFloat", "Results", "Solver time, s", 0.0, _RO),
        "Partial": Prop("App::PropertyBool", "Results", "The run was cancelled early", False,
                        _RO),
        "Backend": Prop("App::PropertyString", "Results", "Tracing backend used", "", _RO),
        "Warnings": Prop("App::PropertyStringList", "Results", "Solver warnings", None, _RO),
        "LightScene": Prop("App::PropertyString", "Results",
                           "The light scene shown (rescaled from the trace), empty = as traced, "
                           "or why the active one cannot be shown", "", _RO),
    }
    for name, key in PER_TARGET.items():
        props[name] = Prop("App::PropertyFloatList", "Results",
                           f"Per target (TargetNames order): {key}, 0 where not reported",
                           None, _RO)
    for name, key in CELL_VALUES.items():
        props[name] = Prop("App::PropertyFloatList", "Results",
                           f"Grid cells' {key}, targets concatenated (CellCounts), each row by "
                           "row (index = iv*nu + iu)", None, HIDDEN)
    return props


#: Properties derived from ResultsJson: recomputed, never saved.
DERIVED = _derived()


class Results(BaseProxy):
    """The results of one analysis run (see the module docstring)."""

    TYPE = TYPE
    PROPERTIES = {
        "ResultsJson": Prop("App::PropertyString", "Results",
                            "The results document (lightsolver.results/1 JSON)", "", HIDDEN),
        "SceneFile": Prop("App::PropertyString", "Results", "Scene file that was solved", "",
                          _RO),
        "ResultsFile": Prop("App::PropertyString", "Results", "Results file written by the run",
                            "", _RO),
        "InputsFingerprint": Prop("App::PropertyString", "Results",
                                  "Fingerprint of the model the run exported "
                                  "(export/fingerprint.py): compared with the model's to tell "
                                  "whether these results are stale", "", HIDDEN),
        **DERIVED,
    }

    @classmethod
    def ensure_properties(cls, obj: Any, set_defaults: bool = False) -> None:
        """The table's properties; the derived ones transient (content not saved)."""
        super().ensure_properties(obj, set_defaults)
        for name in DERIVED:
            status = obj.getPropertyStatus(name) if hasattr(obj, "getPropertyStatus") else []
            if "Transient" not in status and hasattr(obj, "setPropertyStatus"):
                obj.setPropertyStatus(name, "Transient")

    def onChanged(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        if prop == "ResultsJson" and "TargetNames" in obj.PropertiesList:
            if not getattr(obj.Document, "Restoring", False):  # restored: onDocumentRestored
                derive(obj)

    def onDocumentRestored(self, obj: Any) -> None:  # noqa: N802 (FreeCAD API name)
        super().onDocumentRestored(obj)
        derive(obj)


def traced(obj: Any) -> Optional[Dict[str, Any]]:
    """The results document as traced (every control group at full flux), or None when empty
    or unreadable."""
    if obj is None or not obj.ResultsJson:
        return None
    try:
        parsed = json.loads(obj.ResultsJson)
    except ValueError:
        return None
    return parsed if isinstance(parsed, dict) else None


def data(obj: Any) -> Optional[Dict[str, Any]]:
    """The results document shown: the analysis' active light scene rescaled from the traced
    one (objects/light_scene.py), else the traced one; None when there are none."""
    return shown(obj)[0]


_rescaled: Dict[Tuple[str, str], Dict[str, Any]] = {}


def shown(obj: Any) -> Tuple[Optional[Dict[str, Any]], str]:
    """(the results document shown, what it is): the note is "" (as traced), the light scene
    and its levels, or why the active light scene cannot be shown. The note changes with
    every level, so the view providers repaint on it (set last by derive())."""
    from lighting.objects import light_scene

    found = traced(obj)
    if found is None:
        return None, ""
    analysis = analysis_of(obj)
    scene = light_scene.active(analysis) if analysis is not None else None
    if scene is None:
        return found, ""
    typed = read(found)
    if typed is None or not typed.has_contributions:
        return found, (f"'{scene.Label}' not shown: these results were traced without "
                       "contributions; run again")
    try:
        levels = light_scene.levels(scene)
        key = (obj.ResultsJson, json.dumps(sorted(levels.items())))
        if key not in _rescaled:
            import lightsolver

            _rescaled.clear()  # one scene at a time is shown: keep one
            _rescaled[key] = lightsolver.rescale(found, levels)
        return _rescaled[key], light_scene.describe(scene, levels)
    except (ValueError, RuntimeError, ImportError) as exc:
        return found, f"'{scene.Label}' not shown: {exc}"


def _set(obj: Any, name: str, value: Any) -> None:
    if getattr(obj, name) != value:
        setattr(obj, name, value)


def _num(value: Any) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        return 0.0


class _NONE:  # a statistic the target type does not have: every part absent (0 in the lists)
    value = low = high = None


def read(found: Optional[Dict[str, Any]],
         requirements: Optional[Dict[str, Dict[str, float]]] = None) -> Optional[Any]:
    """A results document (``data()``, ``traced()``) as the reader's typed
    ``lightsolver_results.Results`` (solver/results.py ``read``: as the report reads it, older
    layouts migrated, ``requirements`` judged on the estimates of targets the solver did not
    judge), or None for none or no results document."""
    from lighting.solver.results import read as read_results

    if not found:
        return None
    try:
        return read_results(found, requirements)
    except ValueError:  # lightsolver_results.ResultsError: no results document
        return None


def status_of(found: Optional[Dict[str, Any]]) -> str:
    """The analysis' Status for the results document ``found`` (None: none): "not run",
    "done" or "partial results (cancelled)"."""
    typed = read(found)
    if typed is None:
        return "not run"
    return "partial results (cancelled)" if typed.run.partial else "done"


def derive(obj: Any) -> None:
    """Set the derived properties from ResultsJson (all empty when there is none)."""
    found, note = shown(obj)
    typed = read(found)
    targets = typed.targets if typed is not None else []
    _set(obj, "TargetNames", [t.name for t in targets])
    for name, (stat, part) in PER_TARGET.items():
        _set(obj, name, [_num(getattr(getattr(t, stat) or _NONE, part)) for t in targets])
    cells = [t.cell_values for t in targets]
    _set(obj, "CellCounts", [len(c) for c in cells])
    for name, key in CELL_VALUES.items():
        _set(obj, name, [_num(v) for group in cells for v in getattr(group, key)])
    run = typed.run if typed is not None else None
    _set(obj, "Photons", _num(run.photons) if run else 0.0)
    _set(obj, "Seconds", _num(run.seconds) if run else 0.0)
    _set(obj, "Partial", bool(run and run.partial))
    _set(obj, "Backend", run.backend if run else "")
    _set(obj, "Warnings", list(run.warnings) if run else [])
    _set(obj, "LightScene", note)


def index_of(obj: Any, target_name: str) -> Optional[int]:
    """Position of a target in the results' lists, or None when it has no results."""
    names = list(obj.TargetNames)
    return names.index(target_name) if target_name in names else None


def mean_lux(obj: Any, target_name: str) -> Optional[float]:
    """Em of a target, or None when it has no results here."""
    i = index_of(obj, target_name)
    return None if i is None else float(obj.MeanLux[i])


def cells_lux(obj: Any, target_name: str) -> List[float]:
    """Grid cell illuminances of a target (row by row), [] for face targets or none."""
    i = index_of(obj, target_name)
    if i is None:
        return []
    counts = list(obj.CellCounts)
    start = sum(counts[:i])
    return list(obj.CellsLux[start:start + counts[i]])


def of_analysis(analysis: Any) -> Optional[Any]:
    """The results object in an analysis' group, or None."""
    for member in getattr(analysis, "Group", []):
        if proxy_type(member) == TYPE:
            return member
    return None


def analysis_of(obj: Any) -> Optional[Any]:
    """The analysis whose group holds a results object, or None."""
    for parent in obj.InList:
        if proxy_type(parent) == "Lighting::Analysis":
            return parent
    return None


class _CascadeObserver:
    """Removes an analysis' results object with the analysis, however it is deleted (a
    script's ``removeObject`` included; the GUI's view provider does the same first)."""

    def slotDeletedObject(self, obj: Any) -> None:  # noqa: N802 (FreeCAD API name)
        try:
            if proxy_type(obj) != "Lighting::Analysis":
                return
            found = of_analysis(obj)
            if found is not None and found.Document.getObject(found.Name) is not None:
                found.Document.removeObject(found.Name)
        except Exception as exc:  # noqa: BLE001 - an observer must never break a deletion
            import FreeCAD

            FreeCAD.Console.PrintWarning(f"Lighting: results not removed with the analysis: "
                                         f"{exc}\n")


_cascade: Optional[_CascadeObserver] = None


def install_cascade() -> None:
    """Register the observer once (called when an analysis is made or restored)."""
    global _cascade
    if _cascade is None:
        import FreeCAD

        _cascade = _CascadeObserver()
        FreeCAD.addDocumentObserver(_cascade)
