# SPDX-License-Identifier: LGPL-2.1-or-later
"""Placement domain: a face (e.g. the ceiling) where an optimizer may place luminaires.

The domain samples candidate positions on a regular grid over the face (``Resolution``),
``EdgeMargin`` away from its boundary and ``MountingOffset`` off the face along its outward
normal. The export writes them to the scene's ``metadata.placement_domains``;
:func:`optimization_rectangle` gives the optimizer the same lattice as a ``position``
variable (``lighting.optimize_placement``)."""
from __future__ import annotations

import math
from typing import Any, Dict, List, Sequence

import FreeCAD

from lighting.geometry import face_index, face_normal, global_shape, is_planar
from lighting.objects.base import BaseProxy, Prop, READ_ONLY
from lighting.units import vec_m

TYPE = "Lighting::PlacementDomain"
MAX_CANDIDATES = 20000


class PlacementDomain(BaseProxy):
    """Candidate luminaire positions on one planar face."""

    TYPE = TYPE
    PROPERTIES = {
        "Base": Prop("App::PropertyLinkSub", "Domain", "The planar face luminaires may be placed on"),
        "Resolution": Prop("App::PropertyLength", "Domain", "Spacing of candidate positions", 600.0),
        "EdgeMargin": Prop("App::PropertyLength", "Domain",
                           "Smallest distance of a candidate from the face's boundary", 300.0),
        "MountingOffset": Prop("App::PropertyLength", "Domain",
                               "Distance of the luminaires from the face along its normal", 50.0),
        "MaxLuminaires": Prop("App::PropertyInteger", "Domain",
                              "How many luminaires may be placed on this face", 4),
        "MinLuminaires": Prop("App::PropertyInteger", "Domain",
                              "How many luminaires must at least be placed", 1),
        "MinSpacing": Prop("App::PropertyLength", "Domain",
                           "Smallest distance between two placed luminaires (0: any two "
                           "distinct candidates; luminaires never share one)", 0.0),
        "Template": Prop("App::PropertyLink", "Domain",
                         "Luminaire whose type, flux and size placed luminaires copy"),
        "CandidateCount": Prop("App::PropertyInteger", "Domain",
                               "Number of candidate positions", 0, READ_ONLY),
    }

    def execute(self, obj: Any) -> None:
        """Recompute the candidates and show them as points."""
        import Part

        try:
            points, _ = candidates(obj)
        except ValueError as exc:
            FreeCAD.Console.PrintWarning(f"{exc}\n")
            points = []
        obj.CandidateCount = len(points)
        obj.Shape = Part.makeCompound([Part.Vertex(p) for p in points]) if points else Part.Shape()
        obj.Placement = FreeCAD.Placement()


def domain_face(obj: Any) -> Any:
    """The domain's face in global coordinates; ValueError if it is missing or not planar."""
    link = obj.Base
    if not link or link[0] is None:
        raise ValueError(f"Placement domain '{obj.Label}' has no face")
    base, subs = link[0], list(link[1] or [])
    indices = [face_index(s) for s in subs if face_index(s) is not None]
    shape = global_shape(base)
    if not indices:
        if len(shape.Faces) != 1:
            raise ValueError(f"Placement domain '{obj.Label}': select one face of '{base.Label}'")
        indices = [0]
    if indices[0] >= len(shape.Faces):
        raise ValueError(f"Placement domain '{obj.Label}': face {indices[0] + 1} of "
                         f"'{base.Label}' no longer exists")
    face = shape.Faces[indices[0]]
    if not is_planar(face):
        raise ValueError(f"Placement domain '{obj.Label}': the face must be planar")
    return face


def _lattice(obj: Any) -> tuple:
    """(face, normal, offset vector, su, sv, nu, nv, step): the candidate lattice, nu x nv
    points ``step`` apart from (su, sv) in the face's parameter plane, centred on the face."""
    face = domain_face(obj)
    normal = face_normal(face)
    step = float(obj.Resolution)
    if step <= 0.0:
        raise ValueError(f"Placement domain '{obj.Label}': Resolution must be > 0")
    u0, u1, v0, v1 = face.ParameterRange
    # Plane parameters are lengths in mm; centre the lattice on the face.
    nu = max(1, int(math.floor((u1 - u0) / step)) + 1)
    nv = max(1, int(math.floor((v1 - v0) / step)) + 1)
    if nu * nv > 4 * MAX_CANDIDATES:
        raise ValueError(f"Placement domain '{obj.Label}': Resolution {step:g} mm is too fine")
    su = u0 + 0.5 * ((u1 - u0) - (nu - 1) * step)
    sv = v0 + 0.5 * ((v1 - v0) - (nv - 1) * step)
    return face, normal, normal * float(obj.MountingOffset), su, sv, nu, nv, step


def optimization_rectangle(obj: Any) -> Dict[str, Any]:
    """The domain as the rectangle of a ``position`` variable (docs/optimization.md §10, metres):
    its cell centres are the candidate lattice, and ``within`` is the face shrunk by EdgeMargin
    (outer wire and holes), so the admissible cells are the candidates."""
    face, _, offset, su, sv, nu, nv, step = _lattice(obj)
    corner = face.valueAt(su - 0.5 * step, sv - 0.5 * step)
    edge1 = face.valueAt(su + (nu - 0.5) * step, sv - 0.5 * step) - corner
    edge2 = face.valueAt(su - 0.5 * step, sv + (nv - 0.5) * step) - corner
    region = face
    margin = float(obj.EdgeMargin)
    if margin > 0.0:
        region = face.makeOffset2D(-margin)
        if not region.Faces:
            raise ValueError(f"Placement domain '{obj.Label}': EdgeMargin {margin:g} mm leaves "
                             "nothing of the face")
        region = region.Faces[0]

    def ring(wire: Any) -> List[List[float]]:
        return [vec_m(p + offset) for p in wire.discretize(Deflection=0.5)]

    holes = [ring(w) for w in region.Wires if not w.isSame(region.OuterWire)]
    return {"corner": vec_m(corner + offset), "edge1": vec_m(edge1), "edge2": vec_m(edge2),
            "cells": [nu, nv], "within": {"outer": ring(region.OuterWire), "holes": holes}}


def candidate_cells(obj: Any) -> tuple:
    """(list of (i, j, point in mm): the candidates with their cell of the optimization
    rectangle, outward unit normal of the face)."""
    import Part

    face, normal, offset, su, sv, nu, nv, step = _lattice(obj)
    margin = float(obj.EdgeMargin)
    cells: List[tuple] = []
    boundary = Part.Compound(face.Wires)
    for i in range(nu):
        for j in range(nv):
            p = face.valueAt(su + i * step, sv + j * step)
            if not face.isInside(p, 0.01, True):
                continue
            if margin > 0.0 and Part.Vertex(p).distToShape(boundary)[0] < margin:
                continue
            cells.append((i, j, p + offset))
            if len(cells) >= MAX_CANDIDATES:
                return cells, normal
    return cells, normal


def candidates(obj: Any) -> tuple:
    """(list of candidate points in mm, outward unit normal of the face)."""
    cells, normal = candidate_cells(obj)
    return [p for _, _, p in cells], normal


def spread_cells(obj: Any, count: int, spacing_mm: float = 0.0,
                 avoid_mm: Sequence[Sequence[float]] = ()) -> List[tuple]:
    """``count`` distinct candidate cells (i, j) spread evenly over the domain, at least
    ``spacing_mm`` apart and from the points ``avoid_mm`` (luminaires that stay; ValueError if
    the greedy choice cannot keep that): the centres of a k-means partition of the
    candidates (deterministic), each snapped to the nearest free candidate. The optimizer's
    starting layout - the regular array a designer would draw first."""
    import numpy as np

    cells, _ = candidate_cells(obj)
    gap = max(float(spacing_mm), 1e-3)
    if len(avoid_mm):
        fixed = np.asarray(avoid_mm, dtype=float).reshape(-1, 3)
        cells = [c for c in cells
                 if np.min(np.linalg.norm(fixed - [c[2].x, c[2].y, c[2].z], axis=1)) >= gap]
    if len(cells) < count:
        raise ValueError(f"Placement domain '{obj.Label}' has {len(cells)} candidate positions "
                         f"for {count} luminaires: lower MaxLuminaires or Resolution")
    points = np.array([[p.x, p.y, p.z] for _, _, p in cells])
    centres = points[np.linspace(0, len(points) - 1, count).round().astype(int)]
    for _ in range(50):  # Lloyd's iterations
        nearest = np.argmin(((points[:, None, :] - centres[None]) ** 2).sum(-1), axis=1)
        for k in range(count):
            if np.any(nearest == k):
                centres[k] = points[nearest == k].mean(axis=0)
    spacing, chosen = float(spacing_mm), []
    for centre in centres:
        order = np.argsort(((points - centre) ** 2).sum(-1))
        free = [n for n in order if n not in chosen]
        spaced = [n for n in free
                  if all(np.linalg.norm(points[n] - points[c]) >= spacing for c in chosen)]
        if not spaced:
            raise ValueError(f"Placement domain '{obj.Label}': {count} luminaires do not fit "
                             f"{spacing:g} mm apart (MinSpacing, or the luminaire's size); "
                             "lower MaxLuminaires or MinSpacing")
        chosen.append(spaced[0])
    return [(cells[n][0], cells[n][1]) for n in chosen]


def metadata_entry(obj: Any) -> Dict[str, Any]:
    """The domain for the scene's ``metadata.placement_domains`` (metres)."""
    points, normal = candidates(obj)
    template = obj.Template
    return {"name": obj.Name, "label": obj.Label, "max_luminaires": int(obj.MaxLuminaires),
            "min_luminaires": int(obj.MinLuminaires),
            "template": template.Name if template is not None else None,
            "normal": [normal.x, normal.y, normal.z],
            "candidates": [vec_m(p) for p in points]}


def check(obj: Any) -> List[tuple]:
    """Missing face, no candidates, impossible luminaire counts."""
    problems: List[tuple] = []
    try:
        points, _ = candidates(obj)
    except ValueError as exc:
        return [("error", str(exc))]
    if not points:
        problems.append(("warning", f"Placement domain '{obj.Label}' has no candidate positions "
                                    "(face smaller than the edge margin?)"))
    if obj.MaxLuminaires < max(obj.MinLuminaires, 1):
        problems.append(("error", f"Placement domain '{obj.Label}': MaxLuminaires must be >= "
                                  "MinLuminaires and >= 1"))
    elif float(obj.MinSpacing) < 0.0:
        problems.append(("error", f"Placement domain '{obj.Label}': MinSpacing must be >= 0"))
    elif points and obj.MaxLuminaires > len(points):
        problems.append(("warning", f"Placement domain '{obj.Label}': MaxLuminaires "
                                    f"({obj.MaxLuminaires}) exceeds its {len(points)} candidates"))
    return problems
