# SPDX-License-Identifier: LGPL-2.1-or-later
"""Paint targets by illuminance (GUI only): grids cell by cell, face targets by their mean.

Colours come from the analysis' ColorMap and scale (Auto: 0 to a round maximum over its
targets; Fixed: ScaleMinLux..ScaleMaxLux). The values live in App properties, so a reopened
document is painted again without re-running. Painting is triggered from the GUI only: the
view providers' ``updateData`` calls :func:`refresh_later` when a result or display property
changes (App code never calls in here)."""
from __future__ import annotations

from typing import Any, List, Optional

import FreeCAD

from lighting.colormap import Scale, auto_scale
from lighting.objects import analysis as analysis_mod
from lighting.objects.base import objects_of_type, proxy_type

#: Colour and transparency of targets without results.
NO_RESULT_GRID = ((0.55, 0.75, 1.0), 60)
NO_RESULT_FACES = ((0.45, 0.85, 0.45), 40)


def analysis_of(target: Any) -> Optional[Any]:
    """The analysis that produced the target's results, else one that uses the target."""
    doc = target.Document
    if target.ResultAnalysis:
        found = doc.getObject(target.ResultAnalysis)
        if found is not None and proxy_type(found) == analysis_mod.TYPE:
            return found
    for candidate in objects_of_type(doc, analysis_mod.TYPE):
        if any(t.Name == target.Name for t in analysis_mod.targets(candidate)):
            return candidate
    return None


def scale_for(analysis: Any) -> Scale:
    """The colour scale of an analysis."""
    if analysis.ScaleMode == "Fixed":
        return Scale(float(analysis.ScaleMinLux), float(analysis.ScaleMaxLux), analysis.ColorMap)
    values: List[float] = []
    for tgt in analysis_mod.targets(analysis):
        if tgt.HasResults:
            values.append(float(tgt.MeanLux))
            values.extend(float(v) for v in tgt.CellsLux)
    low, high = auto_scale(values)
    return Scale(low, high, analysis.ColorMap)


def paint_target(target: Any, scale: Optional[Scale]) -> None:
    """Colour one target's faces (or show it plain when it has no results)."""
    vobj = getattr(target, "ViewObject", None)
    if vobj is None or target.Shape.isNull():
        return
    faces = len(target.Shape.Faces)
    if not faces:
        return
    proxy = getattr(vobj, "Proxy", None)
    unlit = scale is not None and target.HasResults
    if hasattr(proxy, "set_unlit"):
        proxy.set_unlit(unlit)
    if not unlit:
        colour, transparency = NO_RESULT_GRID if target.TargetType == "Grid" else NO_RESULT_FACES
        vobj.ShapeColor = colour
        vobj.DiffuseColor = [colour] * faces
        vobj.Transparency = transparency
        return
    cells = list(target.CellsLux)
    if target.TargetType == "Grid" and len(cells) == faces:
        colours = scale.colours(cells)
    else:
        colours = [scale.colour(float(target.MeanLux))] * faces
    vobj.Transparency = 0
    vobj.ShapeColor = colours[0]
    vobj.DiffuseColor = colours


def refresh(analysis: Any) -> None:
    """Repaint the analysis' targets and its legend."""
    if not FreeCAD.GuiUp:
        return
    try:
        scale = scale_for(analysis)
        has_results = False
        for tgt in analysis_mod.targets(analysis):
            mine = tgt.HasResults and tgt.ResultAnalysis in ("", analysis.Name)
            has_results = has_results or mine
            paint_target(tgt, scale if mine else None)
        vobj = getattr(analysis, "ViewObject", None)
        proxy = getattr(vobj, "Proxy", None) if vobj is not None else None
        if proxy is not None and hasattr(proxy, "update_legend"):
            proxy.update_legend(scale if has_results and analysis.ShowLegend else None)
    except Exception as exc:  # noqa: BLE001 - painting must never break the document
        FreeCAD.Console.PrintWarning(f"Lighting: cannot paint results: {exc}\n")


def refresh_target(target: Any) -> None:
    """Repaint a target with its analysis' scale (or plain without results)."""
    analysis = analysis_of(target)
    if analysis is not None and target.HasResults:
        refresh(analysis)
    else:
        paint_target(target, None)


_pending: set = set()


def refresh_later(obj: Any) -> None:
    """Repaint an analysis (targets and legend) or a target once control returns to the event
    loop: after FreeCAD's own update of the shape (which resets face colours), and once for
    the many property changes of a results transaction."""
    from PySide import QtCore

    doc_name, name = obj.Document.Name, obj.Name
    key = (doc_name, name)
    if key in _pending:
        return
    _pending.add(key)

    def repaint() -> None:
        _pending.discard(key)
        doc = FreeCAD.listDocuments().get(doc_name)
        found = doc.getObject(name) if doc is not None else None
        if found is None:  # closed or deleted meanwhile
            return
        if proxy_type(found) == analysis_mod.TYPE:
            refresh(found)
        else:
            refresh_target(found)

    QtCore.QTimer.singleShot(0, repaint)
