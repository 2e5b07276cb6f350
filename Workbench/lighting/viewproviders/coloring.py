# SPDX-License-Identifier: LGPL-2.1-or-later
"""Paint targets by illuminance (GUI only): grids cell by cell (work planes, walls, ceilings,
floors alike) with their iso-lux lines, face targets by their mean.

Colours come from the analysis' ColorMap and scale (Auto: 0 to a round maximum over its
targets; Fixed: ScaleMinLux..ScaleMaxLux); the values from the analysis' results object
(objects/results.py), so a reopened document is painted again without re-running. Painting
is triggered from the GUI only: the view providers' ``updateData`` calls :func:`refresh_later`
when a result or display property changes (App code never calls in here)."""
from __future__ import annotations

from typing import Any, List, Optional, Tuple

import FreeCAD
import numpy as np

from lighting import isolux, plots
from lighting.colormap import Scale
from lighting.objects import analysis as analysis_mod
from lighting.objects import results as results_mod
from lighting.objects.base import objects_of_type, proxy_type

#: Colour and transparency of targets without results.
NO_RESULT_GRID = ((0.55, 0.75, 1.0), 60)
NO_RESULT_FACES = ((0.45, 0.85, 0.45), 40)


def analysis_of(target: Any) -> Optional[Any]:
    """The analysis whose results object has results for the target, else one that uses it."""
    doc = target.Document
    users = [a for a in objects_of_type(doc, analysis_mod.TYPE)
             if any(t.Name == target.Name for t in analysis_mod.targets(a))]
    for candidate in users:
        found = results_mod.of_analysis(candidate)
        if found is not None and results_mod.index_of(found, target.Name) is not None:
            return candidate
    return users[0] if users else None


def scale_for(analysis: Any) -> Scale:
    """The colour scale of an analysis (the plan view's too: lighting.plots)."""
    return plots.analysis_scale(analysis)


def isolux_polylines(target: Any, scale: Scale, cells: List[float]) -> Tuple[list, tuple]:
    """Iso-lux lines of a grid's cells as (level, points in mm), a little in front of the
    cells so they are drawn over them, and the offset of their labels (3 % of the grid's
    size toward the front); no lines when the cells do not match the grid."""
    from lighting.objects import target as target_mod

    try:
        rect = target_mod.grid_rectangle(target)
    except ValueError:
        return [], (0.0, 0.0, 0.0)
    if len(cells) != rect.nu * rect.nv or rect.nu * rect.nv > 40000:
        return [], (0.0, 0.0, 0.0)
    values = np.asarray(cells, float).reshape(rect.nv, rect.nu)
    # Lift: enough for the depth buffer at the grid's size, small beside it.
    size_mm = (rect.edge1 + rect.edge2).Length
    lift_mm = max(5.0, 0.002 * size_mm)
    lines = isolux.lines(values, rect.size_m, isolux.levels(scale, cells))
    polylines = [(level, [tuple(rect.point(u, v, lift_mm)) for u, v in points])
                 for level, points in lines]
    return polylines, tuple(rect.normal * (0.03 * size_mm))


def paint_target(target: Any, scale: Optional[Scale], results: Optional[Any] = None) -> None:
    """Colour one target's faces from a results object (plain when it has no results there)."""
    vobj = getattr(target, "ViewObject", None)
    if vobj is None:
        return
    proxy = getattr(vobj, "Proxy", None)
    faces = 0 if target.Shape.isNull() else len(target.Shape.Faces)
    if not faces:
        if hasattr(proxy, "set_isolux"):
            proxy.set_isolux([])
        return
    mean = results_mod.mean_lux(results, target.Name) if results is not None else None
    unlit = scale is not None and mean is not None
    if hasattr(proxy, "set_unlit"):
        proxy.set_unlit(unlit)
    cells = results_mod.cells_lux(results, target.Name) if unlit else []
    if hasattr(proxy, "set_isolux"):
        grid = target.TargetType == "Grid" and unlit
        proxy.set_isolux(*(isolux_polylines(target, scale, cells) if grid else ([],)))
    if not unlit:
        colour, transparency = NO_RESULT_GRID if target.TargetType == "Grid" else NO_RESULT_FACES
        _show(vobj, colour, [colour] * faces, transparency)
        return
    if target.TargetType == "Grid" and len(cells) == faces:
        colours = scale.colours(cells)
    else:
        colours = [scale.colour(mean)] * faces
    _show(vobj, colours[0], colours, 0)


def _bytes(colours: Any) -> List[Tuple[int, ...]]:
    """Colours as the document stores them (8 bits a channel, alpha dropped)."""
    return [tuple(int(round(float(c) * 255.0)) for c in colour[:3]) for colour in colours]


def _show(vobj: Any, shape: Any, diffuse: List[Any], transparency: int) -> None:
    """Set the view properties that differ from what is shown. Writing equal colours again
    marked a document just reopened as modified (its painted colours are saved with it)."""
    if int(vobj.Transparency) != int(transparency):
        vobj.Transparency = transparency
    if _bytes([vobj.ShapeColor]) != _bytes([shape]):
        vobj.ShapeColor = shape
    if _bytes(vobj.DiffuseColor) != _bytes(diffuse):
        vobj.DiffuseColor = diffuse


def refresh(analysis: Any) -> None:
    """Repaint the analysis' targets and its legend from its results object."""
    if not FreeCAD.GuiUp:
        return
    if getattr(analysis.Document, "Restoring", False):
        # A file being read: FreeCAD turns the event loop while it reads (its progress bar),
        # so a timer may fire before the analysis' group holds its results object; painting
        # then showed "no results" and nothing painted again. Paint once it is read.
        refresh_later(analysis)
        return
    try:
        from lighting.viewproviders import annual_coloring, daylight_coloring

        scale = scale_for(analysis)
        found = results_mod.of_analysis(analysis)
        daylight = daylight_coloring.Daylight(analysis, found)  # DF grids: false colours in %
        annual = annual_coloring.Annual(analysis)  # a year's maps, when its Map asks for one
        has_results = False
        painted_annual = False
        for tgt in analysis_mod.targets(analysis):
            if annual.paint(tgt):
                painted_annual = True
                continue
            mine = found is not None and results_mod.index_of(found, tgt.Name) is not None
            has_results = has_results or mine
            if not (mine and daylight.paint(tgt)):
                paint_target(tgt, scale if mine else None, found if mine else None)
        vobj = getattr(analysis, "ViewObject", None)
        proxy = getattr(vobj, "Proxy", None) if vobj is not None else None
        if proxy is not None and hasattr(proxy, "update_legend"):
            shown = (has_results or painted_annual) and analysis.ShowLegend
            if shown and painted_annual:
                proxy.update_legend(annual.scale, **annual.legend())
            elif shown and daylight.scale is not None:
                proxy.update_legend(daylight.scale, **daylight.legend())
            else:
                proxy.update_legend(scale if shown else None)
    except Exception as exc:  # noqa: BLE001 - painting must never break the document
        FreeCAD.Console.PrintWarning(f"Lighting: cannot paint results: {exc}\n")


def refresh_target(target: Any) -> None:
    """Repaint a target with its analysis' scale (or plain without results)."""
    analysis = analysis_of(target)
    if analysis is not None:
        refresh(analysis)
    else:
        paint_target(target, None)


_pending: set = set()
#: How often a repaint asked for while a file is being read looks again.
RESTORE_RETRY_MS = 50


def refresh_later(obj: Any) -> None:
    """Repaint an analysis (targets and legend), a results object's analysis, or a target once
    control returns to the event loop: after FreeCAD's own update of the shape (which resets face colours), and once for
    the many property changes of a results transaction."""
    from PySide import QtCore

    doc_name, name = obj.Document.Name, obj.Name
    key = (doc_name, name)
    if key in _pending:
        return
    _pending.add(key)

    def repaint() -> None:
        doc = FreeCAD.listDocuments().get(doc_name)
        if doc is not None and getattr(doc, "Restoring", False):
            QtCore.QTimer.singleShot(RESTORE_RETRY_MS, repaint)  # still being read (above)
            return
        _pending.discard(key)
        found = doc.getObject(name) if doc is not None else None
        if found is None:  # closed or deleted meanwhile
            return
        if proxy_type(found) == analysis_mod.TYPE:
            refresh(found)
        elif proxy_type(found) == results_mod.TYPE:
            owner = results_mod.analysis_of(found)
            if owner is not None:
                refresh(owner)
        else:
            refresh_target(found)

    QtCore.QTimer.singleShot(0, repaint)
