# SPDX-License-Identifier: LGPL-2.1-or-later
"""A depth-buffered rasteriser for the picture of the model (axonometric.py): each pixel shows
the nearest face at its centre, whatever the faces' order or the room's orientation (a
painter's order is right only where faces can be sorted, and small split triangles only
nearly so). Transparent faces (glass) are blended over the nearest opaque face behind them
(the nearest transparent face per pixel). Vectorised with numpy, in chunks of pixels."""
from __future__ import annotations

from typing import Tuple

import numpy as np

#: Candidate pixels handled at once (memory: a few tens of bytes each).
CHUNK = 1_500_000


def _triangles(quads: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Quads (k, 4, 3) as triangles (0, 1, 2) and (0, 2, 3), with each one's quad index;
    triangles given as degenerate quads (last corner twice) give one."""
    first, second = quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]
    whole = np.any(np.abs(quads[:, 3] - quads[:, 2]) > 0, axis=1)
    tris = np.concatenate([first, second[whole]])
    index = np.concatenate([np.arange(len(quads)), np.flatnonzero(whole)])
    return tris, index


def _nearest(tris: np.ndarray, width: int, height: int) -> Tuple[np.ndarray, np.ndarray]:
    """For faces (n, 3, 3) in pixel coordinates (x, y, depth: larger is nearer): per pixel
    (row-major, y up) the nearest depth (-inf: none) and that face's index (-1)."""
    depth = np.full(width * height, -np.inf)
    owner = np.full(width * height, -1, dtype=np.int64)
    if not len(tris):
        return depth, owner
    x, y, z = tris[:, :, 0], tris[:, :, 1], tris[:, :, 2]
    area = (x[:, 1] - x[:, 0]) * (y[:, 2] - y[:, 0]) - (x[:, 2] - x[:, 0]) * (y[:, 1] - y[:, 0])
    ok = np.abs(area) > 1e-12
    x0 = np.clip(np.floor(x.min(axis=1) - 0.5), 0, width - 1).astype(np.int64)
    x1 = np.clip(np.ceil(x.max(axis=1) - 0.5), 0, width - 1).astype(np.int64)
    y0 = np.clip(np.floor(y.min(axis=1) - 0.5), 0, height - 1).astype(np.int64)
    y1 = np.clip(np.ceil(y.max(axis=1) - 0.5), 0, height - 1).astype(np.int64)
    w, h = x1 - x0 + 1, y1 - y0 + 1
    counts = np.where(ok, w * h, 0)
    ends = np.cumsum(counts)
    start = 0
    while start < len(tris):
        # as many faces as fit CHUNK candidate pixels (at least one)
        stop = max(start + 1, int(np.searchsorted(ends, ends[start] - counts[start] + CHUNK,
                                                  side="right")))
        _chunk(np.arange(start, min(stop, len(tris))), counts, x0, y0, w, x, y, z, area,
               width, depth, owner)
        start = stop
    return depth, owner


def _chunk(faces, counts, x0, y0, w, x, y, z, area, width, depth, owner) -> None:
    n = counts[faces]
    if not n.sum():
        return
    face = np.repeat(faces, n)
    k = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
    px = x0[face] + k % w[face]
    py = y0[face] + k // w[face]
    cx, cy = px + 0.5, py + 0.5
    # barycentric weights of the pixel centre
    l1 = ((cx - x[face, 0]) * (y[face, 2] - y[face, 0])
          - (x[face, 2] - x[face, 0]) * (cy - y[face, 0])) / area[face]
    l2 = ((x[face, 1] - x[face, 0]) * (cy - y[face, 0])
          - (cx - x[face, 0]) * (y[face, 1] - y[face, 0])) / area[face]
    l0 = 1.0 - l1 - l2
    eps = -1e-9
    inside = (l0 >= eps) & (l1 >= eps) & (l2 >= eps)
    if not np.any(inside):
        return
    d = (l0 * z[face, 0] + l1 * z[face, 1] + l2 * z[face, 2])[inside]
    face, pix = face[inside], (py * width + px)[inside]
    # the nearest candidate per pixel (ties: the face given first), then against the buffer
    order = np.lexsort((face, -d, pix))
    pix, d, face = pix[order], d[order], face[order]
    first = np.concatenate([[True], pix[1:] != pix[:-1]])
    pix, d, face = pix[first], d[first], face[first]
    nearer = d > depth[pix]
    depth[pix[nearer]] = d[nearer]
    owner[pix[nearer]] = face[nearer]


def coverage(tris: np.ndarray, width: int, height: int) -> np.ndarray:
    """Which pixels (row-major, y up) have their centre in one of the triangles (k, 3, 2),
    given in pixel coordinates."""
    flat = np.concatenate([tris, np.zeros(tris.shape[:2] + (1,))], axis=-1)
    return _nearest(flat, width, height)[1] >= 0


def render(quads: np.ndarray, colours: np.ndarray, width: int, height: int) -> np.ndarray:
    """RGBA image (height, width, 4), row 0 at the bottom, of faces ``quads`` (k, 4, 3) given
    in pixel coordinates (x right, y up, depth towards the viewer) with ``colours`` (k, 4):
    each pixel the nearest opaque face, with the nearest transparent face in front of it
    blended over (alpha); transparent where no face is."""
    image = np.zeros((height * width, 4))
    if not len(quads):
        return image.reshape(height, width, 4)
    tris, index = _triangles(quads)
    alpha = colours[index, 3]
    solid = alpha >= 1.0
    depth, owner = _nearest(tris[solid], width, height)
    hit = owner >= 0
    image[hit] = colours[index[solid][owner[hit]]]
    glass = ~solid
    if np.any(glass):
        g_depth, g_owner = _nearest(tris[glass], width, height)
        front = (g_owner >= 0) & (g_depth > depth)
        rgba = colours[index[glass][g_owner[front]]]
        a = rgba[:, 3:4]
        under = image[front]
        image[front, :3] = np.where(under[:, 3:4] > 0, under[:, :3] * (1 - a), 0) + \
            rgba[:, :3] * a
        image[front, 3] = under[:, 3] + a[:, 0] * (1 - under[:, 3])
        # over nothing: the glass colour itself at its alpha
        alone = under[:, 3] == 0
        image[np.flatnonzero(front)[alone], :3] = rgba[alone, :3]
    return image.reshape(height, width, 4)
