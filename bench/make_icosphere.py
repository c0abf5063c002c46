#!/usr/bin/env python3
"""make_icosphere.py LEVEL OUT.ply: the unit icosphere subdivided LEVEL times (each face into four,
new vertices on the sphere), as binary little-endian PLY: 10 * 4^LEVEL + 2 vertices, 20 * 4^LEVEL
faces. Level 8 (655,362 vertices, 1,310,720 faces) is the uniformly curved benchmark mesh of
BENCHMARKS.md (no saddle vertex, so an exact field's windows live long: 245M of them from one
vertex); level 7 (327,680 faces, 32M windows) is the quicker one. Stdlib only."""
import math
import struct
import sys


def icosphere(level):
    t = (1.0 + 5.0 ** 0.5) / 2.0
    corners = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
               (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in corners]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
             (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                p = [(verts[a][i] + verts[b][i]) / 2.0 for i in range(3)]
                n = math.sqrt(sum(x * x for x in p))
                verts.append(tuple(x / n for x in p))
                middle[key] = len(verts) - 1
            return middle[key]

        finer = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = finer
    return verts, faces


def main():
    if len(sys.argv) != 3 or not sys.argv[1].isdigit():
        sys.exit("usage: make_icosphere.py LEVEL OUT.ply")
    verts, faces = icosphere(int(sys.argv[1]))
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\nproperty double y\n"
              "property double z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
              % (len(verts), len(faces)))
    with open(sys.argv[2], "wb") as f:
        f.write(header.encode())
        f.write(b"".join(struct.pack("<3d", *v) for v in verts))
        f.write(b"".join(struct.pack("<B3i", 3, *tri) for tri in faces))


if __name__ == "__main__":
    main()
