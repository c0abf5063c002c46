"""cli_common.py - shared pieces of the CLI tests (tests/cli_*.sh run Python through a heredoc and
import this from $TG_SOURCE_DIR/tests): a check counter that ends the script with the summary line
and exit status, and the known-answer mesh, a jittered flat square with a far second component,
whose geodesic distances are Euclidean ones."""
import math
import os
import random
import struct
import sys

passed = failed = 0


def check(cond, what):
    """Counts one check; prints FAIL with what when cond is false."""
    global passed, failed
    if cond:
        passed += 1
    else:
        failed += 1
        print("FAIL:", what)


def finish():
    """Prints "N passed, N failed" and exits non-zero if anything failed."""
    print("%d passed, %d failed" % (passed, failed))
    sys.exit(1 if failed else 0)


def flat_square(tmp, seed, n=8):
    """Writes tmp/flat.obj: the square [0,1]^2 as an (n+1)^2 grid, inner vertices jittered by up to
    0.3 of a cell, each cell split along a random diagonal, plus a lone far triangle (a second
    component). Returns (path, vertices, faces) with 0-based faces in file order."""
    rnd = random.Random(seed)
    vs, fs = [], []
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = i / n, j / n
            if 0 < i < n: x += rnd.uniform(-0.3, 0.3) / n
            if 0 < j < n: y += rnd.uniform(-0.3, 0.3) / n
            vs.append((x, y, 0.0))
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i; b = a + 1; c = a + n + 1; d = c + 1
            fs += [(a, b, d), (a, d, c)] if rnd.random() < 0.5 else [(a, b, c), (b, d, c)]
    base = len(vs)
    vs += [(5, 5, 5), (6, 5, 5), (5, 6, 5)]
    fs.append((base, base + 1, base + 2))
    path = os.path.join(tmp, "flat.obj")
    with open(path, "w") as f:
        for v in vs: f.write("v %.17g %.17g %.17g\n" % v)
        for t in fs: f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))
    return path, vs, fs


def pos_face(vs, fs, fi, b):
    """The point with barycentric coordinates b in face fi."""
    t = fs[fi]
    return [sum(b[k] * vs[t[k]][c] for k in range(3)) for c in range(3)]


def icosphere(level, path):
    """Writes path: the icosahedron subdivided `level` times, vertices on the unit sphere, as a
    binary little-endian PLY (level 7: 163842 vertices, 327680 faces)."""
    t = (1 + 5 ** 0.5) / 2
    V = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    V = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in V]
    F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        mid, nf = {}, []
        def m(a, b):
            k = (a, b) if a < b else (b, a)
            if k not in mid:
                p = [V[a][i] + V[b][i] for i in range(3)]
                n = math.sqrt(sum(x * x for x in p))
                V.append(tuple(x / n for x in p))
                mid[k] = len(V) - 1
            return mid[k]
        for a, b, c in F:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        F = nf
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\nproperty double y\n"
                 "property double z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % (len(V), len(F))).encode())
        f.write(b"".join(struct.pack("<3d", *v) for v in V))
        f.write(b"".join(struct.pack("<B3i", 3, *t) for t in F))
