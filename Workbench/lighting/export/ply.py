# SPDX-License-Identifier: LGPL-2.1-or-later
"""Binary little-endian PLY files (double vertex coordinates, so georeferenced models keep
their precision) and a reader used by the tests."""
from __future__ import annotations

import struct
from typing import List, Sequence, Tuple

from lighting import files


def write_ply(path: str, vertices: Sequence[Sequence[float]],
              triangles: Sequence[Sequence[int]]) -> None:
    """Write a binary PLY with ``double x, y, z`` vertices and ``uchar/uint`` index lists
    (atomically: a failed write leaves the previous file)."""
    header = ("ply\nformat binary_little_endian 1.0\ncomment written by the FreeCAD Lighting "
              f"workbench, metres\nelement vertex {len(vertices)}\nproperty double x\n"
              "property double y\nproperty double z\n"
              f"element face {len(triangles)}\nproperty list uchar uint vertex_indices\n"
              "end_header\n")
    pack_v = struct.Struct("<3d").pack
    pack_f = struct.Struct("<B3I").pack
    files.write_bytes(path, b"".join([header.encode("ascii"),
                                      b"".join(pack_v(*v) for v in vertices),
                                      b"".join(pack_f(3, *t) for t in triangles)]))


def read_ply(path: str) -> Tuple[List[Tuple[float, float, float]], List[Tuple[int, int, int]]]:
    """Read a PLY written by :func:`write_ply` (vertices, triangles)."""
    with open(path, "rb") as stream:
        data = stream.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    nv = nf = 0
    for line in header:
        if line.startswith("element vertex"):
            nv = int(line.split()[2])
        elif line.startswith("element face"):
            nf = int(line.split()[2])
    offset = end
    vertices = [struct.unpack_from("<3d", data, offset + 24 * i) for i in range(nv)]
    offset += 24 * nv
    faces = [struct.unpack_from("<B3I", data, offset + 13 * i)[1:] for i in range(nf)]
    return vertices, faces
