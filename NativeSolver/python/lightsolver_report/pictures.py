# SPDX-License-Identifier: LGPL-2.1-or-later
"""The report's plans and picture of the model, attached to the report after its content is
built (``attach``, called once from ``lightsolver_report.build``):

* ``report.plans``: one :class:`~lightsolver_report.floorplan.Plan` per storey (floor plan to
  scale with luminaires, aiming, calculation areas and observers, and the tables under it);
* ``report.model_picture``: the false-colour picture of the model, decided when the page is
  written: the workbench's 3D-view screenshot when ``report.view_png`` names one (a PNG file),
  else an axonometric drawing of the scene's meshes in the results' colours.

``report.picture_notes`` lists what the pictures could not show (a mesh file not read)."""
from __future__ import annotations

import base64
import math
from typing import Any, Dict, List, Optional, Sequence

import numpy as np

from lightsolver_report import floorplan
from lightsolver_report.meshes import Mesh, load_meshes
from lightsolver_report.planitems import PlanItems, luminaire_row, observer_row, plan_items
from lightsolver_report.floorarea import room_floor_area
from lightsolver_report.section import find_levels, section


def _labels(scene: Dict[str, Any]) -> Dict[str, str]:
    meta = scene.get("metadata") if isinstance(scene.get("metadata"), dict) else {}
    labels = meta.get("labels") if isinstance(meta.get("labels"), dict) else {}
    return {str(k): str(v) for k, v in labels.items()}


def north_deg(scene: Dict[str, Any]) -> Optional[float]:
    """True north from the model's +y axis, degrees counter-clockwise seen from above
    (``metadata.north_deg``), None when the scene does not say."""
    meta = scene.get("metadata") if isinstance(scene.get("metadata"), dict) else {}
    value = meta.get("north_deg")
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    return float(value) % 360.0 if math.isfinite(value) else None


def _all_corners(meshes: Sequence[Mesh]) -> np.ndarray:
    parts = [m.corners for m in meshes if len(m.triangles)]
    return np.concatenate(parts) if parts else np.zeros((0, 3, 3))


def _lowest_item(items: PlanItems) -> Optional[float]:
    heights = [float(m.position[2]) for m in items.luminaires]
    heights += [g.z for g in items.grids] + [o.z for o in items.observers]
    heights += [float(s.centre[2]) for s in items.surfaces]
    return min(heights) if heights else None


def build_plans(scene: Dict[str, Any], meshes: Sequence[Mesh], items: PlanItems,
                salt: str = "floorplan") -> List[floorplan.Plan]:
    """One plan per storey that has something to show."""
    corners = _all_corners(meshes)
    anchors = [(g.z, (float(g.corners[:, 0].min()), float(g.corners[:, 0].max()),
                      float(g.corners[:, 1].min()), float(g.corners[:, 1].max())))
               for g in items.grids if g.horizontal]
    levels = find_levels(corners, anchors, _lowest_item(items))
    north = north_deg(scene)
    plans = []
    for level in levels:
        cut = section(meshes, level)
        mine = items.on(level)
        if not (cut.walls or cut.glass or mine.luminaires or mine.grids or mine.observers):
            continue
        box = floorplan.extent(cut, mine)
        scale = floorplan.choose_scale(box[1] - box[0], box[3] - box[2])
        numbered = len(mine.luminaires) > floorplan.MAX_NAMED
        number = len(plans) + 1
        svg = floorplan.draw(cut, mine, box, scale, f"{salt}{number}", north, numbered)
        title = "Floor plan" if len(levels) == 1 else (
            f"Floor plan, storey at {level.floor_z:+.2f} m")
        plans.append(floorplan.Plan(
            title=title, svg=svg, scale=scale, floor_z=level.floor_z, cut_z=level.cut_z,
            luminaires=[luminaire_row(m, level.floor_z, north) for m in mine.luminaires],
            observers=[observer_row(o, level.floor_z, north) for o in mine.observers],
            areas=[g.label for g in mine.grids] + [s.label for s in mine.surfaces],
            numbered=numbered, aimed=any(m.aimed for m in mine.luminaires),
            bar_m=floorplan.bar_length(box[1] - box[0]), extent=box, level=level, items=mine,
            floor_m2=room_floor_area(meshes, cut.wall_meshes, level,
                                     [tuple(g.corners[:, :2].mean(axis=0))
                                      for g in mine.grids if g.horizontal])))
    return plans


def floor_area(plans: Sequence[floorplan.Plan]) -> Optional[float]:
    """The floor area inside the walls around every horizontal grid of every storey (LENI's
    area where the designer states none); None unless the walls enclose each of them."""
    with_grids = [p for p in plans if p.items is not None and any(
        g.horizontal for g in p.items.grids)]
    if not with_grids or any(p.floor_m2 is None for p in with_grids):
        return None
    return float(sum(p.floor_m2 for p in with_grids))


def png_data_uri(path: str) -> str:
    """A PNG file as a ``data:`` URI (the report page stays one self-contained file)."""
    from lightsolver_report import ReportError

    try:
        with open(path, "rb") as handle:
            data = handle.read()
    except OSError as exc:
        raise ReportError(f"{path}: cannot read the picture of the model: {exc}") from exc
    if not data.startswith(b"\x89PNG\r\n\x1a\n"):
        raise ReportError(f"{path}: the picture of the model is not a PNG file")
    return "data:image/png;base64," + base64.b64encode(data).decode("ascii")


def attach(report: Any, scene: Dict[str, Any], base_dir: str) -> None:
    """Set ``report.plans``, ``report.model_picture`` and ``report.picture_notes``."""
    from lightsolver_report.axonometric import ModelPicture

    labels = _labels(scene)
    meshes, notes = load_meshes(scene, base_dir, labels)
    items = plan_items(scene, meshes, labels)
    report.plans = build_plans(scene, meshes, items)
    # The picture shows the first storey with calculation areas (else the first one).
    shown = [p for p in report.plans if p.items.grids or p.items.surfaces] or report.plans
    first = shown[0] if shown else None
    report.model_picture = ModelPicture(report, meshes, first.items if first else items,
                                        first.level if first else None,
                                        first.extent if first else None, north_deg(scene))
    report.picture_notes = notes
    if hasattr(report, "energy_inputs"):
        from lightsolver_report.model import use_floor_area

        use_floor_area(report, floor_area(report.plans))
