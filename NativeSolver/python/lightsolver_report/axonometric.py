# SPDX-License-Identifier: LGPL-2.1-or-later
"""The false-colour picture of the model: the workbench's 3D-view screenshot when it passes one
(``report.view_png``), else an axonometric drawing of the scene's meshes made here.

The drawing is a parallel projection from above one corner of the room (the room's own
corner: the view turns with a room not aligned with the model's axes), rendered with a depth
buffer (zbuffer.py: each pixel the nearest face, right for any orientation), with the ceiling
and the walls nearest the viewer left out so that the room's inside shows. Surfaces
with results and the cells of calculation grids are coloured by their illuminance on the
report's false-colour scale (a legend in lux); the other surfaces are grey, lighter for a
higher reflectance; glass is a light transparent blue. The triangles are one raster image
inside the SVG (hundreds of thousands of small paths would make the page heavy), the legend
and its text stay vector."""
from __future__ import annotations

import math
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from lightsolver_report import plots, zbuffer
from lightsolver_report.meshes import Mesh
from lightsolver_report.planitems import PlanItems
from lightsolver_report.section import Level, unit_normals
from lightsolver_report.viewframe import room_angle, room_box, rotate_z

#: The viewer: above the plan's lower-left corner (from −x and −y), this far above the horizon.
AZIMUTH_DEG, ELEVATION_DEG = 235.0, 42.0
#: A surface reaching above this height over the floor may be left out when it faces away
#: from the room towards the viewer (near walls, the ceiling).
ENCLOSING_M = 1.8
#: Enclosing surfaces this close to the plan's sides next to the viewer are left out (the plan
#: has a 0.4 m margin around the walls' outside).
NEAR_BAND_M = 0.9
#: At most this many triangles are drawn (a huge mesh by its largest).
MAX_TRIANGLES = 60000
#: Calculation grids with more cells are painted in blocks of cells (their mean).
MAX_CELLS = 40000
RASTER_DPI = 200
#: Calculation grids and surfaces with results are drawn this much nearer (m) than the faces
#: they lie on (a desk top's calculation surface on the desk, a wall's on the wall).
LIFT_M = 0.003


def view_axes(azimuth_deg: float = AZIMUTH_DEG, elevation_deg: float = ELEVATION_DEG
              ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(right, up, towards the viewer) unit vectors of the parallel projection."""
    a, e = math.radians(azimuth_deg), math.radians(elevation_deg)
    toward = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
    right = np.array([-math.sin(a), math.cos(a), 0.0])
    return right, np.cross(toward, right), toward


def largest(corners: np.ndarray, count: int) -> np.ndarray:
    """The ``count`` largest triangles, in their order (a huge mesh is painted by its larger
    triangles: the small ones left out are below the picture's resolution)."""
    if len(corners) <= count:
        return corners
    size = np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]),
                          axis=1)
    keep = np.sort(np.argsort(-size, kind="stable")[:count])
    return corners[keep]


def _grid_cells(corners: np.ndarray, lux: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """A grid's cells as quads (k, 4, 3) with their lux (k,), in blocks of cells (their mean)
    when the grid has more than MAX_CELLS."""
    nv, nu = lux.shape
    k = max(1, math.ceil(math.sqrt(nu * nv / MAX_CELLS)))
    iu, iv = np.arange(0, nu, k), np.arange(0, nv, k)
    sums = np.add.reduceat(np.add.reduceat(lux, iv, axis=0), iu, axis=1)
    counts = np.outer(np.diff(np.append(iv, nv)), np.diff(np.append(iu, nu)))
    values = sums / counts
    o, e1, e2 = corners[0], corners[1] - corners[0], corners[3] - corners[0]
    u = np.append(iu, nu) / nu
    v = np.append(iv, nv) / nv
    quads = []
    for j in range(len(iv)):
        for i in range(len(iu)):
            quads.append([o + u[i] * e1 + v[j] * e2, o + u[i + 1] * e1 + v[j] * e2,
                          o + u[i + 1] * e1 + v[j + 1] * e2, o + u[i] * e1 + v[j + 1] * e2])
    return np.asarray(quads).reshape(-1, 4, 3), values.ravel()


def split_at(corners: np.ndarray, h: float) -> Tuple[np.ndarray, np.ndarray]:
    """Triangles (m, 3, 3) cut by the plane z = ``h``: (the parts below, the parts above),
    each part triangles again (a cut triangle gives one on one side and two on the other)."""
    side = corners[:, :, 2] > h
    count = side.sum(axis=1)
    crossing = (count == 1) | (count == 2)
    below, above = [corners[count == 0]], [corners[count == 3]]
    c, s, lone_up = corners[crossing], side[crossing], count[crossing] == 1
    if len(c):
        lone = np.argmax(s == lone_up[:, None], axis=1)
        rows = np.arange(len(c))
        a, b, d = c[rows, lone], c[rows, (lone + 1) % 3], c[rows, (lone + 2) % 3]
        tb = ((h - a[:, 2]) / (b[:, 2] - a[:, 2]))[:, None]
        td = ((h - a[:, 2]) / (d[:, 2] - a[:, 2]))[:, None]
        p, q = a + tb * (b - a), a + td * (d - a)
        single = np.stack([a, p, q], axis=1)
        pair = np.concatenate([np.stack([p, b, d], axis=1), np.stack([p, d, q], axis=1)])
        pair_up = np.concatenate([~lone_up, ~lone_up])
        below += [single[~lone_up], pair[~pair_up]]
        above += [single[lone_up], pair[pair_up]]
    return np.concatenate(below), np.concatenate(above)


class Painting:
    """What the axonometric shows: the storey's faces cut into slabs at the heights of its
    horizontal calculation grids, and the grids' cells on those planes, each group with its
    colours and whether it carries results (drawn a little nearer than what it lies on). The
    depth buffer decides what is seen; the groups' order does not matter."""

    def __init__(self, cuts: Sequence[float]) -> None:
        self.cuts = sorted(cuts)
        # per slab: polygon groups and their RGBA; per cut: the grids' quads and RGBA
        self.slabs: List[List[Tuple[np.ndarray, np.ndarray]]] = [[] for _ in range(
            len(self.cuts) + 1)]
        self.planes: List[List[Tuple[np.ndarray, np.ndarray]]] = [[] for _ in self.cuts]
        self.values: List[float] = []  # every illuminance shown (for the colour scale)
        self.lifted: set = set()  # ids of the groups drawn LIFT_M nearer (results)

    def slab_parts(self, corners: np.ndarray) -> List[np.ndarray]:
        """The triangles cut into the slabs, bottom slab first."""
        parts = []
        rest = corners
        for h in self.cuts:
            below, rest = split_at(rest, h)
            parts.append(below)
        return parts + [rest]

    def add(self, slab: int, polys: np.ndarray, colours: np.ndarray, lift: bool = False
            ) -> None:
        if len(polys):
            self.slabs[slab].append((polys, colours))
            if lift:
                self.lifted.add(id(polys))

    def add_plane(self, height: float, polys: np.ndarray, colours: np.ndarray) -> bool:
        """Grid quads on one of the cut planes; False when ``height`` is not one."""
        for i, h in enumerate(self.cuts):
            if abs(h - height) < 1e-9:
                self.planes[i].append((polys, colours))
                self.lifted.add(id(polys))
                return True
        return False

    def layers(self) -> List[List[Tuple[np.ndarray, np.ndarray]]]:
        """The groups in painting order: slab 0, plane 0, slab 1, plane 1, ..."""
        out = []
        for i, slab in enumerate(self.slabs):
            out.append(slab)
            if i < len(self.planes):
                out.append(self.planes[i])
        return out


def _grey(mesh: Mesh, normals: np.ndarray, angle_deg: float = 0.0) -> np.ndarray:
    """Grey by reflectance, lighter for faces turned to a light from above the viewer's left
    (so that the walls and the floor are told apart; the light turns with the room, as the
    viewer does); glass light blue and transparent."""
    light = rotate_z(np.array([-0.55, 0.25, 0.8]), angle_deg)
    shade = 0.6 + 0.4 * np.abs(normals @ (light / np.linalg.norm(light)))
    if mesh.kind == "glass":
        rgba = np.tile([0.72, 0.85, 0.95, 0.35], (len(normals), 1))
        rgba[:, :3] *= shade[:, None]
        return rgba
    base = 0.42 + 0.5 * mesh.reflectance
    g = np.clip(base * shade, 0.0, 1.0)
    return np.stack([g, g, g, np.ones_like(g)], axis=1)


def _visible(corners: np.ndarray, level: Level, box: Tuple[float, float, float, float],
             toward: np.ndarray, enclosing: bool, angle_deg: float = 0.0) -> np.ndarray:
    """Which triangles to paint: those of the storey, less, for an enclosing mesh (walls,
    ceiling, tall cupboards: reaching above ENCLOSING_M over the floor), those whose side
    facing the room's centre faces away from the viewer (the near walls' faces, the ceiling)
    and those within NEAR_BAND_M of the room's sides next to the viewer (what stands in the
    near walls: window frames, panes). ``box`` and ``toward`` are in the room's frame, the
    model turned by −``angle_deg`` (room_angle), so that a rotated room loses its own near
    walls."""
    low, high = corners[:, :, 2].min(axis=1), corners[:, :, 2].max(axis=1)
    keep = (low < level.top_z - 0.05) & (high > level.floor_z - 0.05)
    if not enclosing:
        return keep
    corners = rotate_z(corners, -angle_deg) if angle_deg else corners
    x0, x1, y0, y1 = box
    centre = np.array([(x0 + x1) / 2, (y0 + y1) / 2, level.floor_z + 1.2])
    mid = corners.mean(axis=1)
    normals = unit_normals(corners)
    inward = np.sign(np.sum(normals * (centre - mid), axis=1))
    facing = np.sum(normals * inward[:, None] * toward, axis=1)
    near = np.zeros(len(corners), dtype=bool)
    for axis, (lo, hi) in enumerate(((x0, x1), (y0, y1))):
        if toward[axis] < -0.2:
            near |= mid[:, axis] < lo + NEAR_BAND_M
        elif toward[axis] > 0.2:
            near |= mid[:, axis] > hi - NEAR_BAND_M
    return keep & (facing >= 0.02) & ~near


def paint_scene(meshes: Sequence[Mesh], items: PlanItems, level: Level,
                surface_lux: Dict[str, float], grid_lux: Dict[str, np.ndarray],
                box: Tuple[float, float, float, float], toward: np.ndarray,
                cmap, norm, angle_deg: float = 0.0) -> Painting:
    """The storey's surfaces and calculation grids, coloured (``cmap``/``norm`` for values);
    ``box`` and ``toward`` in the room's frame (see :func:`_visible`)."""
    mesh_lux = {s.mesh: surface_lux[s.name] for s in items.surfaces if s.name in surface_lux}
    grids = [g for g in items.grids if g.name in grid_lux and grid_lux[g.name].size]
    out = Painting(sorted({round(g.z, 9) for g in grids if g.horizontal} |
                          {level.floor_z - 1e-6, level.floor_z + 0.01}))
    total = sum(len(m.triangles) for m in meshes) or 1
    for mesh in meshes:
        corners = mesh.corners
        if not len(corners):
            continue
        enclosing = float(corners[:, :, 2].max()) > level.floor_z + ENCLOSING_M
        corners = corners[_visible(corners, level, box, toward, enclosing, angle_deg)]
        corners = largest(corners, max(1000, int(MAX_TRIANGLES * len(mesh.triangles) / total)))
        for slab, part in enumerate(out.slab_parts(corners)):
            if mesh.name in mesh_lux:
                rgba = np.tile(cmap(norm(mesh_lux[mesh.name])), (len(part), 1))
            else:
                rgba = _grey(mesh, unit_normals(part), angle_deg)
            out.add(slab, part, rgba, lift=mesh.name in mesh_lux)
    for grid in grids:
        quads, values = _grid_cells(grid.corners, grid_lux[grid.name])
        rgba = cmap(norm(values))
        if not (grid.horizontal and out.add_plane(round(grid.z, 9), quads, rgba)):
            out.add(int(np.searchsorted(out.cuts, grid.z)), quads, rgba, lift=True)
    return out


def _luminaire_polys(items: PlanItems, size: float, angle_deg: float = 0.0) -> np.ndarray:
    """Luminaires as small flat shapes: their outline, or a square of ``size`` about a point
    source (along the room's walls)."""
    polys = []
    for mark in items.luminaires:
        if mark.outline is not None and np.ptp(mark.outline, axis=0).max() > size:
            polys.append(mark.outline)
        else:
            h = size / 2
            square = np.array([(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)])
            polys.append(mark.position + rotate_z(square, angle_deg))
    return np.asarray(polys).reshape(-1, 4, 3)


def _quads(polys: np.ndarray) -> np.ndarray:
    """Triangles (k, 3, 3) as degenerate quads (the last corner twice), so that triangles and
    grid cells share one array (cells stay whole: no seam along a diagonal)."""
    return polys if polys.shape[1] == 4 else polys[:, [0, 1, 2, 2]]


def _all_faces(painting: Painting) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every face of the painting as quads (k, 4, 3) with its colour and whether it is lifted
    (carries results)."""
    quads, colours, lifted = [], [], []
    for layer in painting.layers():
        for polys, rgba in layer:
            quads.append(_quads(polys))
            colours.append(rgba)
            lifted.append(np.full(len(polys), id(polys) in painting.lifted))
    if not quads:
        return np.zeros((0, 4, 3)), np.zeros((0, 4)), np.zeros(0, dtype=bool)
    return np.concatenate(quads), np.concatenate(colours), np.concatenate(lifted)


def projected(painting: Painting, azimuth_deg: float = AZIMUTH_DEG
              ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The painting's faces in the view from ``azimuth_deg``: (plan coordinates (k, 4, 2),
    depth towards the viewer (k, 4), colours (k, 4)). Faces with results are LIFT_M nearer;
    faces turned away from the viewer a tenth of a millimetre farther, so that of two faces
    in contact (a wall's foot on the floor) the one facing the viewer is seen."""
    right, up, toward = view_axes(azimuth_deg)
    quads, colours, lifted = _all_faces(painting)
    flat = np.stack([quads @ right, quads @ up], axis=-1)
    normals = np.cross(quads[:, 1] - quads[:, 0], quads[:, 2] - quads[:, 0])
    away = normals @ toward < 0
    depth = quads @ toward + (np.where(lifted, LIFT_M, 0.0) - np.where(away, 1e-4, 0.0))[:, None]
    return flat, depth, colours


def rasterise(flat: np.ndarray, depth: np.ndarray, colours: np.ndarray,
              bounds: Tuple[float, float, float, float], px_w: int, px_h: int) -> np.ndarray:
    """The depth-buffered image (px_h, px_w, 4), row 0 at the bottom, of projected faces over
    ``bounds`` (x0, x1, y0, y1)."""
    x0, x1, y0, y1 = bounds
    pixels = np.stack([(flat[..., 0] - x0) * px_w / (x1 - x0),
                       (flat[..., 1] - y0) * px_h / (y1 - y0), depth], axis=-1)
    return zbuffer.render(pixels, colours, px_w, px_h)


def draw(painting: Painting, lamps: np.ndarray, norm, cmap, salt: str,
         azimuth_deg: float = AZIMUTH_DEG, quantity: str = "E [lx]") -> str:
    """The parallel projection, rendered with a depth buffer into one raster image (RASTER_DPI,
    not antialiased: no seams, a small file), the luminaires over it as outlines and a colour
    bar labelled ``quantity`` (lux; the daylight factor in percent) when values show."""
    from matplotlib.collections import PolyCollection
    from matplotlib.cm import ScalarMappable

    right, up, _ = view_axes(azimuth_deg)
    flat, depth, colours = projected(painting, azimuth_deg)
    every = np.concatenate([flat.reshape(-1, 2), np.stack(
        [lamps @ right, lamps @ up], axis=-1).reshape(-1, 2)]) if len(lamps) else \
        flat.reshape(-1, 2)
    if not len(every):
        every = np.zeros((1, 2))
    lo, hi = every.min(axis=0), every.max(axis=0)
    size = np.maximum(hi - lo, 1e-6)
    bar = bool(painting.values)
    plot_w = plots.PAGE_WIDTH_IN - (1.0 if bar else 0.2)
    plot_h = plot_w * size[1] / size[0]
    if plot_h > 4.4:
        plot_h, plot_w = 4.4, 4.4 * size[0] / size[1]
    fig = plots._figure(plot_w + (1.0 if bar else 0.2), plot_h + 0.2)
    width, height = fig.get_size_inches()
    ax = fig.add_axes((0.1 / width, 0.1 / height, plot_w / width, plot_h / height))
    pad = 0.01 * size.max()
    x0, x1, y0, y1 = lo[0] - pad, hi[0] + pad, lo[1] - pad, hi[1] + pad
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal", adjustable="box")
    ax.set_axis_off()
    px_w, px_h = max(1, round(plot_w * RASTER_DPI)), max(1, round(plot_h * RASTER_DPI))
    image = rasterise(flat, depth, colours, (x0, x1, y0, y1), px_w, px_h)
    ax.imshow(image, extent=(x0, x1, y0, y1), origin="lower", interpolation="none",
              aspect="auto", zorder=1)
    if len(lamps):
        ax.add_collection(PolyCollection(np.stack([lamps @ right, lamps @ up], axis=-1),
                                         facecolors="#fff6cc", edgecolors="#4d4d4d",
                                         linewidths=0.5, zorder=3))
    if bar:
        cax = fig.add_axes(((0.1 + plot_w + 0.25) / width, 0.15 * plot_h / height + 0.1 / height,
                            0.14 / width, 0.7 * plot_h / height))
        colorbar = fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), cax=cax)
        colorbar.set_label(quantity, fontsize=7)
        colorbar.ax.tick_params(labelsize=7, length=2)
        colorbar.outline.set_linewidth(0.6)
    return plots._svg(fig, salt, dpi=RASTER_DPI)


class ModelPicture:
    """The report's picture of the model, decided when the page is written: the screenshot
    ``report.view_png`` (a PNG file) when set, else the axonometric drawing (made once)."""

    def __init__(self, report: Any, meshes: Sequence[Mesh], items: PlanItems,
                 level: Optional[Level], box: Optional[Tuple[float, float, float, float]],
                 north_deg: Optional[float] = None, salt: str = "model") -> None:
        self.report, self.meshes, self.items = report, meshes, items
        self.level, self.box, self.north_deg, self.salt = level, box, north_deg, salt
        self._svg: Optional[str] = None
        self._angle: Optional[float] = None

    @property
    def view_png(self) -> Optional[str]:
        value = getattr(self.report, "view_png", None)
        return str(value) if value else None

    @property
    def shown(self) -> bool:
        """Whether there is a picture (a screenshot, or geometry to draw)."""
        return bool(self.view_png) or (self.level is not None and any(
            len(m.triangles) for m in self.meshes))

    @property
    def caption(self) -> str:
        if self.view_png:
            return ("The model in the 3D view of the design software, surfaces in false "
                    "colours by their illuminance.")
        if _results(self.report)[2] != "E [lx]":
            shown = "Daylight-factor grids (cell by cell) in false colours by their daylight factor"
        else:
            shown = ("Calculation grids (cell by cell) and calculation surfaces (their mean) in "
                     "false colours by their illuminance")
        return (f"Axonometric view of the model from above {_side(self.north_deg, self.angle)}; "
                "the ceiling and the walls nearest the viewer are left out. "
                f"{shown}; other surfaces in grey, lighter for a higher reflectance; "
                "glass light blue; luminaires pale yellow.")

    def __html__(self) -> str:
        if self.view_png:
            from lightsolver_report.pictures import png_data_uri

            return (f'<img class="model-view" src="{png_data_uri(self.view_png)}" '
                    'alt="The model in false colours" '
                    'style="display: block; max-width: 100%; height: auto;">')
        return self.svg

    @property
    def svg(self) -> str:
        """The axonometric drawing (empty without geometry)."""
        if self._svg is None:
            self._svg = self._draw() if self.shown else ""
        return self._svg

    def painting(self) -> Tuple[Painting, Any, Any]:
        """What the drawing paints, with its colour scale (``norm``) and map."""
        from matplotlib.colors import Normalize

        surface_lux, grid_lux, self.quantity = _results(self.report)
        names = {s.name for s in self.items.surfaces} | {g.name for g in self.items.grids}
        values = [v for k, v in surface_lux.items() if k in names]
        for k, lux in grid_lux.items():
            if k in names:
                values.extend(np.asarray(lux, dtype=float).ravel().tolist())
        norm = Normalize(*plots.colour_range(np.asarray(values, dtype=float)))
        cmap = plots.colormap()
        _, _, toward = view_axes()  # in the room's frame: the standard view
        painting = paint_scene(self.meshes, self.items, self.level, surface_lux, grid_lux,
                               room_box(self.meshes, self.level, self.angle), toward, cmap,
                               norm, self.angle)
        painting.values = values
        return painting, norm, cmap

    @property
    def angle(self) -> float:
        """The room's orientation (room_angle): the view turns with it."""
        if self._angle is None:
            self._angle = room_angle(self.meshes, self.level) if self.level else 0.0
        return self._angle

    def _lamp_size(self) -> float:
        """A point source's square: a 48th of the plan's size."""
        x0, x1, y0, y1 = self.box
        return max(x1 - x0, y1 - y0) / 48.0

    def _draw(self) -> str:
        painting, norm, cmap = self.painting()
        lamps = _luminaire_polys(self.items, self._lamp_size(), self.angle)
        return draw(painting, lamps, norm, cmap, self.salt, AZIMUTH_DEG + self.angle,
                    self.quantity)


def _side(north_deg: Optional[float], angle_deg: float = 0.0) -> str:
    """Where the viewer is: "its south-west corner" (...) when north is known, else the plan's
    corner (the room's, for a room turned by ``angle_deg``)."""
    if north_deg is None:
        return "the lower left corner of the plan" if not angle_deg else (
            "the room's corner at the lower left of the plan")
    bearing = (90.0 - AZIMUTH_DEG - angle_deg + north_deg) % 360.0  # clockwise from north
    names = ("north", "north-east", "east", "south-east", "south", "south-west", "west",
             "north-west")
    return f"its {names[int(((bearing + 22.5) % 360.0) // 45.0)]} corner"


def _results(report: Any) -> Tuple[Dict[str, float], Dict[str, np.ndarray], str]:
    """Each calculation surface's mean and each grid's cells (lux), from the report's areas,
    and the colour bar's label. Daylight-factor grids are coloured by their daylight factor
    (percent) when no illuminance area is drawn, else left grey (one scale per picture)."""
    surfaces, grids, daylight = {}, {}, {}
    for area in getattr(report, "areas", []) or []:
        df = getattr(area, "daylight", None)
        if df is not None:
            if df.percent is not None and df.percent.size:
                daylight[area.name] = np.asarray(df.percent, dtype=float)
        elif area.type == "surface" and area.em is not None and area.em.value is not None:
            surfaces[area.name] = float(area.em.value)
        elif area.type == "grid" and area.grid is not None and area.grid.lux.size:
            grids[area.name] = np.asarray(area.grid.lux, dtype=float)
    if daylight and not surfaces and not grids:
        return {}, daylight, "D [%]"
    return surfaces, grids, "E [lx]"
