# SPDX-License-Identifier: LGPL-2.1-or-later
"""Floor plans to scale: per storey a horizontal section at 1 m above the floor (walls cut in
dark grey, windows in blue), what lies below it seen from above (floor, desks, tables), the
calculation grids and surfaces outlined, the luminaires with their labels and aiming arrows,
the observers with their lines of sight, a scale bar, the scale at which the page prints it
and, when the scene gives one, a north arrow (``metadata.north_deg``).

The plan is matplotlib SVG (plots.py's conventions: byte-stable ids, text as text). Its axes
are sized so that one metre of the model is 1000/scale mm on the printed A4 page."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Optional, Tuple

import numpy as np

from lightsolver_report import plots
from lightsolver_report.planitems import (LuminaireMark, LuminaireRow, ObserverMark,
                                         ObserverRow, PlanItems)
from lightsolver_report.section import Level, Section

#: Scales a plan may print at (1:n), as on architects' drawings.
SCALES = (10, 20, 25, 50, 75, 100, 125, 150, 200, 250, 300, 400, 500, 750, 1000, 1250, 1500,
          2000, 2500, 5000, 7500, 10000)
#: The largest drawing on the page (A4 portrait within the report's margins), mm.
MAX_W_MM, MAX_H_MM = 156.0, 170.0
#: Around the drawing: tick labels left, ticks + scale bar + north arrow below, mm.
LEFT_MM, RIGHT_MM, TOP_MM, BOTTOM_MM = 9.0, 3.0, 2.0, 19.0
MM = 1.0 / 25.4  # inches per millimetre
LABEL_PT = 6.5
#: Above this many faces and edges below the section, they are one raster image in the SVG
#: (at RASTER_DPI); the walls, symbols and text stay vector.
RASTER_ABOVE, RASTER_DPI = 3000, 200
#: More luminaires than this on one plan are labelled with their numbers (the table names them).
MAX_NAMED = 40

WALL = "#3c3c3c"
GLASS = "#2f86c8"
GLASS_BAND = "#cfe6f7"
FLOOR = "#f3f0ea"
CUT_FURNITURE = "#a3a3a3"
FURNITURE = "#dcdcdc"
EDGE = "#6e6e6e"
GRID = "#1f6fb2"
LUMINAIRE = "#1a1a1a"
AIM = "#d9480f"
OBSERVER = "#7b3fa0"


@dataclass
class Plan:
    """One storey's plan as printed: the picture and what its tables list."""

    title: str
    svg: str
    scale: int
    floor_z: float
    cut_z: float
    luminaires: List[LuminaireRow] = field(default_factory=list)
    observers: List[ObserverRow] = field(default_factory=list)
    areas: List[str] = field(default_factory=list)
    numbered: bool = False
    aimed: bool = False  # some luminaire has an aiming arrow
    bar_m: float = 1.0
    extent: Tuple[float, float, float, float] = (0.0, 1.0, 0.0, 1.0)
    level: Optional[Level] = None
    items: Optional[PlanItems] = None
    #: The floor area inside the walls around the storey's horizontal grids (None: the walls
    #: enclose none of them; section.room_floor_area).
    floor_m2: Optional[float] = None


def choose_scale(width_m: float, height_m: float) -> int:
    """The smallest standard scale 1:n at which the drawing fits the page."""
    need = max(width_m * 1000.0 / MAX_W_MM, height_m * 1000.0 / MAX_H_MM, 1e-9)
    for n in SCALES:
        if n >= need:
            return n
    return int(10 ** math.ceil(math.log10(need)))


def bar_length(width_m: float) -> float:
    """A round scale bar length (1, 2 or 5 × 10^k m) of at most a third of the drawing."""
    best = 0.01
    for k in range(-2, 6):
        for m in (1.0, 2.0, 5.0):
            if m * 10.0 ** k <= width_m / 3.0:
                best = m * 10.0 ** k
    return best


def extent(section: Section, items: PlanItems, margin: float = 0.4
           ) -> Tuple[float, float, float, float]:
    """(xmin, xmax, ymin, ymax) of the plan: the cut walls and every marked item, with a
    margin; the top view alone where nothing else is there."""
    pts = [items.points()[:, :2]]
    bounds = section.bounds()
    if bounds is not None:
        pts.append(np.array([[bounds[0], bounds[2]], [bounds[1], bounds[3]]]))
    allp = np.concatenate(pts)
    if not len(allp) and section.layers:
        allp = np.concatenate([l.triangles.reshape(-1, 2) for l in section.layers])
    allp = allp[np.all(np.isfinite(allp), axis=1)]
    if not len(allp):
        return (-1.0, 1.0, -1.0, 1.0)
    x0, y0 = allp.min(axis=0) - margin
    x1, y1 = allp.max(axis=0) + margin
    # at least 2 m across, so that symbols and labels have room
    cx, cy, w, h = (x0 + x1) / 2, (y0 + y1) / 2, max(x1 - x0, 2.0), max(y1 - y0, 2.0)
    return (float(cx - w / 2), float(cx + w / 2), float(cy - h / 2), float(cy + h / 2))


class _Labels:
    """Greedy label placement in paper millimetres: each label takes the first of eight
    places around its symbol that overlaps nothing placed before (else the least bad)."""

    PLACES = ((1, 1), (1, -1), (-1, 1), (-1, -1), (0, 1), (0, -1), (1, 0), (-1, 0))

    def __init__(self, ax, box: Tuple[float, float, float, float], mm_per_m: float) -> None:
        self.ax, self.box, self.k = ax, box, mm_per_m
        self.taken: List[Tuple[float, float, float, float]] = []

    def block(self, x: float, y: float, half_w_mm: float, half_h_mm: Optional[float] = None
              ) -> None:
        """Reserve a symbol's rectangle (half sizes in mm) around (x, y) metres."""
        hw = half_w_mm / self.k
        hh = (half_w_mm if half_h_mm is None else half_h_mm) / self.k
        self.taken.append((x - hw, x + hw, y - hh, y + hh))

    def _overlap(self, b) -> float:
        total = 0.0
        for t in self.taken:
            w = min(b[1], t[1]) - max(b[0], t[0])
            h = min(b[3], t[3]) - max(b[2], t[2])
            if w > 0 and h > 0:
                total += w * h
        x0, x1, y0, y1 = self.box
        outside = (max(0, x0 - b[0]) + max(0, b[1] - x1)) * (b[3] - b[2]) + (
            max(0, y0 - b[2]) + max(0, b[3] - y1)) * (b[1] - b[0])
        return total + 10.0 * outside

    def place(self, text: str, x: float, y: float, half_w_mm: float, colour: str,
              first: Tuple[int, int] = (1, 1), half_h_mm: Optional[float] = None) -> None:
        """Write ``text`` beside the symbol at (x, y) whose half sizes are given in mm."""
        w = (0.62 * LABEL_PT * 0.3528 * len(text) + 0.6) / self.k  # metres
        h = (LABEL_PT * 0.3528 + 0.6) / self.k
        gx = (half_w_mm + 0.5) / self.k
        gy = ((half_w_mm if half_h_mm is None else half_h_mm) + 0.5) / self.k
        best = None
        for dx, dy in (first,) + self.PLACES:
            bx = x + dx * gx + (0 if dx > 0 else -w if dx < 0 else -w / 2)
            by = y + dy * gy + (0 if dy > 0 else -h if dy < 0 else -h / 2)
            b = (bx, bx + w, by, by + h)
            score = self._overlap(b)
            if best is None or score < best[0] - 1e-12:
                best = (score, b)
            if score <= 0:
                break
        b = best[1]
        self.taken.append(b)
        self.ax.text(b[0] + 0.3 / self.k, (b[2] + b[3]) / 2, text, fontsize=LABEL_PT,
                     color=colour, ha="left", va="center", zorder=9,
                     bbox={"boxstyle": "square,pad=0.1", "facecolor": "white",
                           "edgecolor": "none", "alpha": 0.8})


def top_view(section: Section) -> List[Tuple[np.ndarray, str, str, float, float]]:
    """What lies below the section, seen from above, in painting order: (shape, face colour,
    edge colour, line width, height) of every mesh's faces (on the floor in the floor's
    colour, higher ones grey by reflectance) and drawn edges (a face's is "none"), from the
    lowest up across all meshes: a face hides the edges and faces below it, its own mesh's too
    (a table's legs under its top), and an edge is drawn over a face at its own height (the
    face's outline)."""
    floor_z = section.level.floor_z
    found: List[Tuple[Tuple[float, int], Tuple[np.ndarray, str, str, float, float]]] = []
    for layer in section.layers:
        if len(layer.triangles):
            on_floor = layer.heights <= floor_z + 0.03
            colours = np.where(on_floor, FLOOR, plots_grey(layer.mesh.reflectance))
            found.extend(((float(h), 0), (t, str(c), str(c), 0.25, float(h)))
                         for t, c, h in zip(layer.triangles, colours, layer.heights))
        if len(layer.edges):
            colour = "#b4b0a8" if layer.top_z <= floor_z + 0.03 else EDGE
            found.extend(((float(h), 1), (e, "none", colour, 0.4, float(h)))
                         for e, h in zip(layer.edges, layer.edge_heights))
    found.sort(key=lambda item: item[0])  # stable: ties keep the meshes' order
    return [item for _, item in found]


def _draw_layers(ax, section: Section, raster: bool) -> None:
    """The top view below the section (:func:`top_view`) as one collection, so that its
    painting order holds across meshes."""
    from matplotlib.collections import PolyCollection

    items = top_view(section)
    if not items:
        return
    shapes, faces, edges, widths, _ = zip(*items)
    ax.add_collection(PolyCollection(list(shapes), facecolors=list(faces),
                                     edgecolors=list(edges), linewidths=list(widths),
                                     closed=True, zorder=1.0, rasterized=raster))


def plots_grey(reflectance: float) -> str:
    """The top view's shade of a surface: lighter for a lighter material."""
    v = 0.80 + 0.14 * min(1.0, max(0.0, reflectance))
    return f"#{int(round(v * 255)):02x}{int(round(v * 255)):02x}{int(round(v * 255)):02x}"


def _fill_loops(ax, loops: List[np.ndarray], colour: str, zorder: float) -> None:
    """Closed cut outlines filled as solids (holes where one lies inside another)."""
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path

    from lightsolver_report.section import fill_orientation

    if not loops:
        return
    verts, codes = [], []
    for loop in fill_orientation(loops):
        verts.extend(loop.tolist() + [loop[0].tolist()])
        codes.extend([Path.MOVETO] + [Path.LINETO] * (len(loop) - 1) + [Path.CLOSEPOLY])
    ax.add_patch(PathPatch(Path(verts, codes), facecolor=colour, edgecolor=WALL,
                           linewidth=0.5, zorder=zorder))


def _draw_section(ax, section: Section) -> None:
    """Cut walls dark, cut furniture mid grey (solids filled, cut single faces as thick
    lines), glass as a light band with a line."""
    from lightsolver_report.section import solids

    for lines, colour, width, z in ((section.furniture, CUT_FURNITURE, 1.2, 4),
                                    (section.walls, WALL, 2.6, 4.05)):
        fill, rest = solids(lines)
        _fill_loops(ax, fill, colour, z)
        for line in rest:
            pts = np.vstack([line.points, line.points[:1]]) if line.closed else line.points
            ax.plot(pts[:, 0], pts[:, 1], color=WALL, linewidth=width,
                    solid_capstyle="projecting", solid_joinstyle="miter", zorder=z)
    for line in section.glass:  # a pane: a light band with a line in its middle
        pts = np.vstack([line.points, line.points[:1]]) if line.closed else line.points
        ax.plot(pts[:, 0], pts[:, 1], color=GLASS_BAND, linewidth=2.6, zorder=4.1,
                solid_capstyle="butt")
        ax.plot(pts[:, 0], pts[:, 1], color=GLASS, linewidth=0.7, zorder=4.2)


def _draw_targets(ax, items: PlanItems, labels: _Labels) -> None:
    from matplotlib.collections import LineCollection
    from matplotlib.patches import Polygon

    for i, grid in enumerate(items.grids):
        xy = grid.corners[:, :2]
        ax.add_patch(Polygon(xy, closed=True, facecolor=GRID, alpha=0.07, edgecolor="none",
                             zorder=3))
        ax.add_patch(Polygon(xy, closed=True, fill=False, edgecolor=GRID, linewidth=0.8,
                             linestyle=(0, (4, 2)), zorder=3.1, gid=f"grid{i}"))
    for surface in items.surfaces:
        if len(surface.edges):
            ax.add_collection(LineCollection(surface.edges[:, :, :2], colors=GRID,
                                             linewidths=0.8, linestyles=(0, (1.2, 1.2)),
                                             zorder=3.1))
    for grid in items.grids:  # names inside the top-left corner of each grid
        labels.place(grid.label, *top_left(grid.corners[:, :2]), 0.3, GRID, first=(1, -1))
    for surface in items.surfaces:  # horizontal: inside the top-left corner, like a grid's
        if surface.horizontal and len(surface.edges):
            labels.place(surface.label, *top_left(surface.edges[:, :, :2].reshape(-1, 2)), 0.3,
                         GRID, first=(1, -1))
        else:
            labels.place(surface.label, float(surface.centre[0]), float(surface.centre[1]),
                         0.8, GRID)


def top_left(xy: np.ndarray) -> Tuple[float, float]:
    """The corner of an outline's points nearest the top left of their box (the box's corner
    itself for an outline along the axes; a turned grid's own corner, not a point outside
    it)."""
    k = int(np.argmin((xy[:, 0] - xy[:, 0].min()) + (xy[:, 1].max() - xy[:, 1])))
    return float(xy[k, 0]), float(xy[k, 1])


def _arrow(ax, start, end, colour: str, width: float, zorder: float, gid: str) -> None:
    from matplotlib.patches import FancyArrowPatch

    ax.add_patch(FancyArrowPatch(tuple(start), tuple(end), arrowstyle="-|>", mutation_scale=7,
                                 color=colour, linewidth=width, shrinkA=0, shrinkB=0,
                                 zorder=zorder, gid=gid))


def arrow_end(start: np.ndarray, direction: np.ndarray, length: float,
              box: Tuple[float, float, float, float]) -> Optional[np.ndarray]:
    """The tip of an arrow of ``length`` from ``start`` along the plan projection of
    ``direction``, shortened to stay in ``box``; None when the direction is (nearly)
    vertical."""
    d = np.asarray(direction[:2], dtype=np.float64)
    norm = float(np.linalg.norm(d))
    if norm < 1e-6:
        return None
    d = d / norm
    x0, x1, y0, y1 = box
    limit = length
    for i, (lo, hi) in enumerate(((x0, x1), (y0, y1))):
        if d[i] > 1e-12:
            limit = min(limit, (hi - start[i]) / d[i])
        elif d[i] < -1e-12:
            limit = min(limit, (lo - start[i]) / d[i])
    return np.asarray(start[:2], dtype=np.float64) + max(0.0, limit) * d


def aim_tip(mark: LuminaireMark, floor_z: float, length: float,
            box: Tuple[float, float, float, float]) -> Optional[np.ndarray]:
    """The tip of an aimed luminaire's arrow: its aiming point on the floor, or an arrow of
    ``length`` along the beam where the beam does not reach the floor in the plan."""
    if not mark.aimed:
        return None
    point = mark.aiming_point(floor_z)
    x0, x1, y0, y1 = box
    if point is not None and x0 <= point[0] <= x1 and y0 <= point[1] <= y1:
        return point[:2]
    return arrow_end(mark.position, mark.aim, length, box)


def _half_size_mm(mark: LuminaireMark, mm_per_m: float) -> Tuple[float, float]:
    """Half the symbol's width and height on paper: an outline's, at least the 1.3 mm
    circle's."""
    if mark.outline is None:
        return 1.3, 1.3
    size = 0.5 * np.ptp(mark.outline[:, :2], axis=0) * mm_per_m
    return max(1.3, float(size[0])), max(1.3, float(size[1]))


def _draw_luminaires(ax, items: PlanItems, floor_z: float, box, labels: _Labels) -> None:
    """Symbols (outline with a cross, or a crossed circle) and aiming arrows to the aiming
    point on the floor (x) or along the beam."""
    from matplotlib.patches import Circle, Polygon

    r = 1.3 / labels.k  # symbol radius: 1.3 mm on paper
    for mark in items.luminaires:
        x, y = float(mark.position[0]), float(mark.position[1])
        if max(_half_size_mm(mark, labels.k)) > 1.3:
            xy = mark.outline[:, :2]
            ax.add_patch(Polygon(xy, closed=True, facecolor="white", edgecolor=LUMINAIRE,
                                 linewidth=0.7, zorder=6))
            ends = [(xy[0], xy[2]), (xy[1], xy[3])]
        else:
            ax.add_patch(Circle((x, y), r, facecolor="white", edgecolor=LUMINAIRE,
                                linewidth=0.7, zorder=6))
            c = r * math.cos(0.25 * math.pi)
            ends = [((x - c, y - c), (x + c, y + c)), ((x - c, y + c), (x + c, y - c))]
        for a, b in ends:
            ax.plot([a[0], b[0]], [a[1], b[1]], color=LUMINAIRE, linewidth=0.35, zorder=6.1)
        labels.block(x, y, *_half_size_mm(mark, labels.k))
        tip = aim_tip(mark, floor_z, 12.0 / labels.k, box)
        if tip is not None:
            _arrow(ax, (x, y), tip, AIM, 0.8, 7, f"aim{mark.number}")
            ax.plot([tip[0]], [tip[1]], marker="x", markersize=3.5, markeredgewidth=0.8,
                    color=AIM, zorder=7)


def _label_luminaires(items: PlanItems, labels: _Labels, numbered: bool) -> None:
    for mark in items.luminaires:
        hw, hh = _half_size_mm(mark, labels.k)
        labels.place(str(mark.number) if numbered else mark.label, float(mark.position[0]),
                     float(mark.position[1]), hw, LUMINAIRE, half_h_mm=hh)


def observer_arrows(mark: ObserverMark, length: float, box) -> List[Tuple[np.ndarray,
                                                                          np.ndarray]]:
    """(start, tip) in plan of every line of sight of an observer (an observer grid: every
    eye × every direction), ``length`` long, kept inside ``box``."""
    out = []
    for p in mark.positions:
        for d in mark.directions:
            tip = arrow_end(p, d, length, box)
            if tip is not None:
                out.append((np.asarray(p[:2], dtype=np.float64), tip))
    return out


def _draw_observers(ax, items: PlanItems, box, labels: _Labels) -> None:
    """Eyes as dots, lines of sight as arrows (an observer grid's shorter; none where an
    observer grid has more than 48 of them)."""
    for i, mark in enumerate(items.observers):
        many = len(mark.positions) * len(mark.directions) > 48
        length = (3.5 if mark.grid else 9.0) / labels.k
        for j, (start, tip) in enumerate([] if many else observer_arrows(mark, length, box)):
            _arrow(ax, start, tip, OBSERVER, 0.7 if mark.grid else 0.9, 8, f"sight{i}-{j}")
        ax.plot(mark.positions[:, 0], mark.positions[:, 1], linestyle="none", marker="o",
                markersize=2.4 if mark.grid else 3.6, color=OBSERVER, zorder=8.1)
        for p in mark.positions:
            labels.block(float(p[0]), float(p[1]), 1.0)


def _label_observers(items: PlanItems, labels: _Labels) -> None:
    for mark in items.observers:
        first = mark.positions[0]
        labels.place(mark.label, float(first[0]), float(first[1]), 1.4, OBSERVER,
                     first=(-1, 1))


def _scale_bar(fig, ax, length_m: float, scale: int, bottom_in: float) -> None:
    """Alternating black and white blocks ``length_m`` long in the plan's own metres (the
    x data transform), under the drawing, with the print scale beside it."""
    from matplotlib.patches import Rectangle
    from matplotlib.transforms import blended_transform_factory

    trans = blended_transform_factory(ax.transData, fig.dpi_scale_trans)
    x0 = ax.get_xlim()[0]
    y, h = bottom_in, 1.4 * MM
    lead = round(length_m / 10 ** math.floor(math.log10(length_m) + 1e-9))
    parts = 4 if lead == 2 else 5  # 2 m as 4 × 0.5 m; 1 m and 5 m as 5 × 0.2 m and 5 × 1 m
    step = length_m / parts
    for i in range(parts):
        ax.add_artist(Rectangle((x0 + i * step, y), step, h, transform=trans, clip_on=False,
                                facecolor="black" if i % 2 == 0 else "white",
                                edgecolor="black", linewidth=0.5, gid=f"scalebar{i}"))
    for value, align in ((0.0, "center"), (length_m, "center")):
        ax.text(x0 + value, y - 0.6 * MM, f"{value:g}" + (" m" if value else ""),
                transform=trans, ha=align, va="top", fontsize=6.5, clip_on=False)
    ax.text(x0 + length_m + 3.0 / 1000.0 * scale, y + h / 2,
            f"Scale 1:{scale} (A4)", transform=trans, ha="left", va="center",
            fontsize=7, clip_on=False)


def _north_arrow(fig, north_deg: float, centre_in: Tuple[float, float]) -> None:
    """A compass: a circle with an arrow across it to north and an N beyond its tip
    (``north_deg``: true north from +y, counter-clockwise)."""
    from matplotlib.patches import Circle, FancyArrowPatch

    a = math.radians(north_deg)
    d = np.array([-math.sin(a), math.cos(a)])
    r = 4.0 * MM
    cx, cy = centre_in
    inches = fig.dpi_scale_trans

    def at(k: float) -> Tuple[float, float]:
        return (cx + d[0] * r * k, cy + d[1] * r * k)

    fig.add_artist(Circle((cx, cy), r, transform=inches, fill=False, edgecolor="black",
                          linewidth=0.5))
    fig.add_artist(FancyArrowPatch(at(-1.0), at(1.0), transform=inches, arrowstyle="-|>",
                                   mutation_scale=8, color="black", linewidth=0.8, shrinkA=0,
                                   shrinkB=0, gid="north"))
    x, y = at(1.5)
    fig.text(x, y, "N", transform=inches, ha="center", va="center", fontsize=7.5,
             fontweight="bold")


def draw(section: Section, items: PlanItems, box: Tuple[float, float, float, float],
         scale: int, salt: str, north_deg: Optional[float] = None,
         numbered: bool = False) -> str:
    """The plan as SVG text: ``box`` (metres) at 1:``scale``."""
    import matplotlib
    from matplotlib.ticker import MultipleLocator

    x0, x1, y0, y1 = box
    mm_per_m = 1000.0 / scale
    w_in, h_in = (x1 - x0) * mm_per_m * MM, (y1 - y0) * mm_per_m * MM
    fig = plots._figure(w_in + (LEFT_MM + RIGHT_MM) * MM, h_in + (TOP_MM + BOTTOM_MM) * MM)
    width, height = fig.get_size_inches()
    with matplotlib.rc_context(plots._rc(salt)):
        ax = fig.add_axes((LEFT_MM * MM / width, BOTTOM_MM * MM / height, w_in / width,
                           h_in / height))
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
        ax.set_aspect("equal", adjustable="box")
        tick = bar_length(max(x1 - x0, y1 - y0)) / 2 if max(x1 - x0, y1 - y0) > 8 else 1.0
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_locator(MultipleLocator(tick))
        ax.tick_params(labelsize=6, length=2, colors="#777777", width=0.4)
        for spine in ax.spines.values():
            spine.set_edgecolor("#999999")
            spine.set_linewidth(0.4)
        labels = _Labels(ax, box, mm_per_m)
        raster = sum(len(l.triangles) + len(l.edges) for l in section.layers) > RASTER_ABOVE
        _draw_layers(ax, section, raster)
        _draw_section(ax, section)
        _draw_luminaires(ax, items, section.level.floor_z, box, labels)
        _draw_observers(ax, items, box, labels)
        _draw_targets(ax, items, labels)  # outlines and their labels
        _label_luminaires(items, labels, numbered)
        _label_observers(items, labels)
        bar = bar_length(x1 - x0)
        _scale_bar(fig, ax, bar, scale, 7.0 * MM)
        if north_deg is not None:
            _north_arrow(fig, north_deg, (width - RIGHT_MM * MM - 6.0 * MM, 7.5 * MM))
    return plots._svg(fig, salt, dpi=RASTER_DPI)
