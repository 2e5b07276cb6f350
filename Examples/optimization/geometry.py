"""Procedural triangle meshes for the optimization examples (no downloaded models).

Every builder returns a Mesh whose triangles wind counter-clockwise seen from the side their
normal points to ("outward" for solids, "inward" for rooms), as docs/scene-format.md requires for
surface targets. Meshes are written as compact binary little-endian PLY.
"""
from __future__ import annotations

import math
import struct
from dataclasses import dataclass, field
from pathlib import Path

Vec = tuple[float, float, float]


@dataclass
class Mesh:
    """Vertices (metres) and triangles (vertex indices)."""

    vertices: list[Vec] = field(default_factory=list)
    triangles: list[tuple[int, int, int]] = field(default_factory=list)

    def add(self, other: "Mesh") -> "Mesh":
        """Appends another mesh in place and returns self."""
        base = len(self.vertices)
        self.vertices += other.vertices
        self.triangles += [(a + base, b + base, c + base) for a, b, c in other.triangles]
        return self

    def flipped(self) -> "Mesh":
        """The same surface facing the other way."""
        return Mesh(list(self.vertices), [(a, c, b) for a, b, c in self.triangles])

    def translated(self, d: Vec) -> "Mesh":
        """A copy moved by d."""
        return Mesh([(x + d[0], y + d[1], z + d[2]) for x, y, z in self.vertices],
                    list(self.triangles))

    def quad(self, a: Vec, b: Vec, c: Vec, d: Vec) -> None:
        """Adds the quad a-b-c-d (counter-clockwise seen from its front)."""
        i = len(self.vertices)
        self.vertices += [a, b, c, d]
        self.triangles += [(i, i + 1, i + 2), (i, i + 2, i + 3)]


def box(x0: float, y0: float, z0: float, x1: float, y1: float, z1: float,
        bottom: bool = True, top: bool = True) -> Mesh:
    """Axis-aligned box with outward faces; bottom=False leaves the base open (for objects
    standing on a floor, whose base would otherwise coincide with it), top=False the top (when
    the top is a separate mesh, e.g. a target)."""
    m = Mesh()
    if top:
        m.quad((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1))
    if bottom:
        m.quad((x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0))
    m.quad((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))  # -y
    m.quad((x1, y1, z0), (x0, y1, z0), (x0, y1, z1), (x1, y1, z1))  # +y
    m.quad((x0, y1, z0), (x0, y0, z0), (x0, y0, z1), (x0, y1, z1))  # -x
    m.quad((x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1))  # +x
    return m


def grid_quad(corner: Vec, e1: Vec, e2: Vec, nu: int, nv: int) -> Mesh:
    """A parallelogram split into nu x nv quads, front toward e1 x e2."""
    m = Mesh()
    for j in range(nv + 1):
        for i in range(nu + 1):
            u, v = i / nu, j / nv
            m.vertices.append(tuple(corner[k] + u * e1[k] + v * e2[k] for k in range(3)))
    for j in range(nv):
        for i in range(nu):
            a = j * (nu + 1) + i
            m.triangles += [(a, a + 1, a + nu + 2), (a, a + nu + 2, a + nu + 1)]
    return m


def sphere(c: Vec, r: float, segments: int, rings: int) -> Mesh:
    """UV sphere with outward faces."""
    m = Mesh()
    for j in range(rings + 1):
        th = math.pi * j / rings
        for i in range(segments):
            ph = 2 * math.pi * i / segments
            m.vertices.append((c[0] + r * math.sin(th) * math.cos(ph),
                               c[1] + r * math.sin(th) * math.sin(ph), c[2] + r * math.cos(th)))
    for j in range(rings):
        for i in range(segments):
            a, b = j * segments + i, j * segments + (i + 1) % segments
            if j > 0:
                m.triangles.append((a, a + segments, b))
            if j < rings - 1:
                m.triangles.append((b, a + segments, b + segments))
    return m


def cylinder(c: Vec, r: float, h: float, segments: int, stacks: int = 1) -> Mesh:
    """Vertical cylinder (axis +z from c), outward side and top cap, open bottom."""
    m = Mesh()
    for j in range(stacks + 1):
        for i in range(segments):
            ph = 2 * math.pi * i / segments
            m.vertices.append((c[0] + r * math.cos(ph), c[1] + r * math.sin(ph),
                               c[2] + h * j / stacks))
    for j in range(stacks):
        for i in range(segments):
            a, b = j * segments + i, j * segments + (i + 1) % segments
            m.triangles += [(a, b, b + segments), (a, b + segments, a + segments)]
    top = len(m.vertices)
    m.vertices.append((c[0], c[1], c[2] + h))
    ring = stacks * segments
    m.triangles += [(top, ring + i, ring + (i + 1) % segments) for i in range(segments)]
    return m


def cone(c: Vec, r: float, h: float, segments: int, stacks: int) -> Mesh:
    """Upright cone (apex at c + h z), outward lateral surface, no base."""
    m = Mesh()
    for j in range(stacks):
        rr = r * (1 - j / stacks)
        for i in range(segments):
            ph = 2 * math.pi * i / segments
            m.vertices.append((c[0] + rr * math.cos(ph), c[1] + rr * math.sin(ph),
                               c[2] + h * j / stacks))
    apex = len(m.vertices)
    m.vertices.append((c[0], c[1], c[2] + h))
    for j in range(stacks - 1):
        for i in range(segments):
            a, b = j * segments + i, j * segments + (i + 1) % segments
            m.triangles += [(a, b, b + segments), (a, b + segments, a + segments)]
    last = (stacks - 1) * segments
    m.triangles += [(last + i, last + (i + 1) % segments, apex) for i in range(segments)]
    return m


def biconvex_lens(c: Vec, aperture: float, radius: float, segments: int, rings: int) -> Mesh:
    """Closed symmetric biconvex lens (two spherical caps of curvature `radius` meeting on a
    rim of radius `aperture` in the plane z = c.z), outward faces."""
    sag = radius - math.sqrt(radius * radius - aperture * aperture)
    m = Mesh()

    def cap(sign: int) -> None:
        base = len(m.vertices)
        m.vertices.append((c[0], c[1], c[2] + sign * sag))
        for j in range(1, rings + 1):
            rho = aperture * j / rings
            z = sign * (math.sqrt(radius * radius - rho * rho) - (radius - sag))
            for i in range(segments):
                ph = 2 * math.pi * i / segments
                m.vertices.append((c[0] + rho * math.cos(ph), c[1] + rho * math.sin(ph), c[2] + z))
        ring = lambda j, i: base + 1 + (j - 1) * segments + i % segments  # noqa: E731
        tris = [(base, ring(1, i), ring(1, i + 1)) for i in range(segments)]
        for j in range(1, rings):
            for i in range(segments):
                tris += [(ring(j, i), ring(j + 1, i), ring(j + 1, i + 1)),
                         (ring(j, i), ring(j + 1, i + 1), ring(j, i + 1))]
        m.triangles += tris if sign > 0 else [(a, c_, b) for a, b, c_ in tris]

    cap(+1)
    cap(-1)
    return m  # the two rims coincide in position: a closed surface for tracing


def write_ply(path: Path, mesh: Mesh) -> None:
    """Binary little-endian PLY: float vertices, uchar-counted int faces."""
    head = ("ply\nformat binary_little_endian 1.0\n"
            f"element vertex {len(mesh.vertices)}\nproperty float x\nproperty float y\n"
            f"property float z\nelement face {len(mesh.triangles)}\n"
            "property list uchar int vertex_indices\nend_header\n").encode()
    body = bytearray()
    for v in mesh.vertices:
        body += struct.pack("<3f", *v)
    for t in mesh.triangles:
        body += struct.pack("<B3i", 3, *t)
    path.write_bytes(head + bytes(body))
