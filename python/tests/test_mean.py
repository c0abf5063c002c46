"""Mesh.geodesic_mean and Mesh.bezier against independent oracles: on a flat jittered grid (no
face folds) the mean is the weighted average of the points and the Bezier curve the planar one in
Bernstein form (by both methods), both to 1e-12 of the diagonal; the CLI (`trigeo mean --json`, `trigeo path
--bezier`) gives the same numbers bit for bit; bad input raises InvalidArgumentError; a progress
callback that says stop, or raises, stops the call."""
import csv
import json
import math
import os
import subprocess

import numpy as np
import pytest

import trigeo
from conftest import cli_path


def flat_grid(n=16, seed=5):
    """The unit square tilted into space, inner vertices jittered by up to 0.15 of a cell (no face
    can fold), random diagonals; returns (vertices, faces, e1, e2, origin)."""
    rnd = np.random.default_rng(seed)
    uv = []
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = i / n, j / n
            if 0 < i < n: x += rnd.uniform(-0.15, 0.15) / n
            if 0 < j < n: y += rnd.uniform(-0.15, 0.15) / n
            uv.append((x, y))
    faces = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i; b = a + 1; c = a + n + 1; d = c + 1
            faces += [(a, b, d), (a, d, c)] if rnd.random() < 0.5 else [(a, b, c), (b, d, c)]
    uv = np.array(uv)
    origin, e1, e2 = np.array([1.0, 2.0, -3.0]), np.array([0.0, 0.8, 0.6]), np.array([1.0, 0.0, 0.0])
    v = origin + uv[:, :1] * e1 + uv[:, 1:] * e2
    return v, np.array(faces)


def face_points(rnd, faces, k):
    out = []
    for _ in range(k):
        f = int(rnd.integers(len(faces)))
        a = rnd.random(); b = rnd.random() * (1 - a)
        out.append(trigeo.SurfacePoint.face(f, (a, b, 1 - a - b)))
    return out


def position(v, faces, p):
    return sum(p.bary[k] * v[faces[p.index][k]] for k in range(3))


@pytest.fixture(scope="module")
def grid():
    v, f = flat_grid()
    return trigeo.Mesh(v, f), v, f


def test_mean_is_the_weighted_average(grid):
    m, v, f = grid
    rnd = np.random.default_rng(1)
    for k in (1, 2, 5, 9):
        pts = face_points(rnd, f, k)
        w = rnd.uniform(0.1, 4.0, k)
        want = sum(wi * position(v, f, p) for wi, p in zip(w, pts)) / w.sum()
        r = m.geodesic_mean(pts, weights=w)
        assert np.linalg.norm(r.xyz - want) <= 1e-12 * math.sqrt(2), (r.xyz, want)
        assert r.status == "converged" and r.uniqueness == "unique" and r.gradient_norm <= 1e-10
        assert isinstance(r.point, trigeo.SurfacePoint)
        assert np.array_equal(m.geodesic_mean(pts, weights=w, uniqueness=False).xyz, r.xyz)
    # unit weights, positions as points, a start elsewhere
    pts = face_points(rnd, f, 4)
    xyz = np.array([position(v, f, p) for p in pts])
    r = m.geodesic_mean(xyz, start=0, tolerance=1e-12)
    assert np.linalg.norm(r.xyz - xyz.mean(axis=0)) <= 1e-12 * math.sqrt(2)


def test_bezier_is_the_planar_curve(grid):
    m, v, f = grid
    rnd = np.random.default_rng(2)
    for degree, method in [(d, how) for d in range(1, 6) for how in ("paths", "logmap")]:
        ctrl = face_points(rnd, f, degree + 1)
        cx = np.array([position(v, f, p) for p in ctrl])
        n = 11
        xyz, faces, bary = m.bezier(ctrl, samples=n, method=method)
        assert xyz.shape == (n, 3) and faces.shape == (n,) and bary.shape == (n, 3)
        for j in range(n):
            t = j / (n - 1)
            want = sum(math.comb(degree, i) * t ** i * (1 - t) ** (degree - i) * cx[i] for i in range(degree + 1))
            assert np.linalg.norm(xyz[j] - want) <= 1e-12 * math.sqrt(2), (degree, j, xyz[j], want)
            # the face and barycentrics name the same point
            assert np.linalg.norm(bary[j] @ v[f[faces[j]]] - xyz[j]) <= 1e-14
    # vertex control points: the ends are those vertices
    xyz, faces, bary = m.bezier([0, 40, 288], samples=3)
    assert np.array_equal(xyz[0], v[0]) and np.array_equal(xyz[2], v[288])
    for j in range(3):
        assert np.linalg.norm(np.einsum("k,kc->c", bary[j], v[f[faces[j]]]) - xyz[j]) <= 1e-14, (j, faces[j], bary[j])


def test_same_numbers_as_the_cli(grid, tmp_path):
    m, v, f = grid
    path = tmp_path / "grid.obj"
    with open(path, "w") as out:
        out.writelines("v %r %r %r\n" % tuple(x) for x in v)
        out.writelines("f %d %d %d\n" % tuple(t + 1) for t in f)
    mesh = trigeo.load(path)
    rnd = np.random.default_rng(3)
    pts = face_points(rnd, f, 6)
    w = rnd.uniform(0.5, 2.0, 6)
    specs = ["f:%d:%r,%r,%r" % (p.index, *p.bary) for p in pts]
    (tmp_path / "p.txt").write_text("\n".join(specs) + "\n")
    (tmp_path / "w.txt").write_text("\n".join(repr(x) for x in w) + "\n")
    r = subprocess.run([cli_path(), "mean", str(path), "--points", str(tmp_path / "p.txt"), "--weights",
                        str(tmp_path / "w.txt"), "--json"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    py = mesh.geodesic_mean(pts, weights=w)
    assert doc["xyz"] == py.xyz.tolist() and doc["iterations"] == py.iterations and doc["uniqueness"] == py.uniqueness
    r = subprocess.run([cli_path(), "path", str(path), "--bezier", ";".join(specs[:4]), "--samples", "9", "--json"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    xyz, _, _ = mesh.bezier(pts[:4], samples=9)
    assert json.loads(r.stdout)["xyz"] == xyz.tolist()
    r = subprocess.run([cli_path(), "path", str(path), "--bezier", ";".join(specs[:4]), "--samples", "9",
                        "--bezier-method", "logmap", "--json"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    xyz, _, _ = mesh.bezier(pts[:4], samples=9, method="logmap")
    assert json.loads(r.stdout)["xyz"] == xyz.tolist()


def test_bad_input(grid):
    m, v, f = grid
    two = trigeo.Mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [5, 5, 5], [6, 5, 5], [5, 6, 5.0]]),
                      np.array([[0, 1, 2], [3, 4, 5]]))
    bad = trigeo.InvalidArgumentError
    for call in (lambda: m.geodesic_mean([]), lambda: m.geodesic_mean([0, 1], weights=[1, 2, 3]),
                 lambda: m.geodesic_mean([0, 1], weights=[1, -1]), lambda: m.geodesic_mean([0, 1], weights=[1, math.nan]),
                 lambda: m.geodesic_mean([0, 1], weights=[0, 0]), lambda: m.geodesic_mean([0, 1], weights=["a", "b"]),
                 lambda: m.geodesic_mean([0, 1], tolerance=-1), lambda: m.geodesic_mean([0, 1], max_iterations=0),
                 lambda: m.geodesic_mean([0, 10 ** 9]), lambda: two.geodesic_mean([0, 4]),
                 lambda: two.geodesic_mean([0, 1], start=4), lambda: m.bezier([0, 1], samples=1),
                 lambda: m.bezier([]), lambda: two.bezier([0, 1, 4]), lambda: m.bezier([0, 1], method="exact")):
        with pytest.raises(bad):
            call()
    with pytest.raises(bad, match="different components"):
        two.geodesic_mean([0, 4])


def test_progress_stops(grid):
    m, v, f = grid
    with pytest.raises(trigeo.CancelledError):
        m.geodesic_mean([0, 100, 200], progress=lambda fraction: False)

    def boom(fraction):
        raise KeyError("from the callback")

    with pytest.raises(KeyError):
        m.geodesic_mean([0, 100, 200], progress=boom)
    with pytest.raises(KeyError):
        m.bezier([0, 100, 200], samples=5, progress=boom)
    assert m.geodesic_mean([0, 100, 200], progress=lambda fraction: None).status == "converged"


def clip(poly, g, h):
    """The polygon (corners in space) clipped to the half-space x . g <= h."""
    out = []
    for i in range(len(poly)):
        a, b = poly[i], poly[(i + 1) % len(poly)]
        va, vb = a @ g - h, b @ g - h
        if va <= 0:
            out.append(a)
        if (va <= 0) != (vb <= 0):
            out.append(a + va / (va - vb) * (b - a))
    return out


def planar_lloyd(v, f, s, iters):
    """The planar Lloyd iteration of the continuous domain from sites s, computed independently of
    the library: each face clipped by the straight bisector half-planes of all the sites, each site
    moved to its polygonal cell's centroid, the energy the exact integral of |x - s|^2 over the
    cells. Returns (sites, vertex labels, energies)."""
    s = np.array(s, dtype=float)
    energies = []
    for it in range(iters + 1):
        d2 = ((v[:, None, :] - s[None, :, :]) ** 2).sum(axis=2)
        lab = d2.argmin(axis=1)
        energy, moment, mass = 0.0, np.zeros_like(s), np.zeros(len(s))
        for t in f:
            for i in range(len(s)):
                poly = [v[t[0]], v[t[1]], v[t[2]]]
                for j in range(len(s)):
                    if j != i and poly:
                        poly = clip(poly, 2 * (s[j] - s[i]), s[j] @ s[j] - s[i] @ s[i])
                for c in range(1, len(poly) - 1):  # fan: area, centroid, polar moment
                    a, b, e = poly[0], poly[c], poly[c + 1]
                    area = 0.5 * np.linalg.norm(np.cross(b - a, e - a))
                    cen = (a + b + e) / 3
                    l2 = (b - a) @ (b - a) + (e - a) @ (e - a) + (e - b) @ (e - b)
                    energy += area * ((cen - s[i]) @ (cen - s[i]) + l2 / 36)
                    moment[i] += area * cen
                    mass[i] += area
        energies.append(energy)
        if it < iters:
            s[mass > 0] = moment[mass > 0] / mass[mass > 0, None]
    return s, lab, np.array(energies)


def test_centroidal_voronoi_is_planar_lloyd(grid, tmp_path):
    m, v, f = grid
    sites, labels, energies = m.centroidal_voronoi(6, iterations=5, seed=3, tolerance=1e-300)
    start = m.farthest_point_sampling(6, seed=3)[0]
    want_s, want_l, want_e = planar_lloyd(v, f, v[start], len(energies) - 1)
    assert len(energies) >= 4 and np.all(np.abs(energies - want_e) <= 1e-12 * want_e), (energies, want_e)
    assert np.array_equal(labels, want_l)
    # the CLI's sites (sample --cvt -o .csv) are the same bits
    path = tmp_path / "grid.obj"
    with open(path, "w") as out:
        out.writelines("v %r %r %r\n" % tuple(x) for x in v)
        out.writelines("f %d %d %d\n" % tuple(t + 1) for t in f)
    r = subprocess.run([cli_path(), "sample", str(path), "--count", "6", "--seed", "3", "--cvt", "--iterations", "5",
                        "-o", str(tmp_path / "s.csv"), "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    rows = list(csv.reader(open(tmp_path / "s.csv")))
    assert rows[0] == ["i", "site", "x", "y", "z"] and len(rows) == 7
    cli_xyz = np.array([[float(x) for x in row[2:5]] for row in rows[1:]])
    assert np.linalg.norm(cli_xyz - want_s, axis=1).max() <= 1e-12 * math.sqrt(2), (cli_xyz, want_s)


def test_centroidal_voronoi_energy_never_rises():
    spot = trigeo.load(os.path.join(os.path.dirname(__file__), "..", "..", "data", "nvd_spot.obj"))
    sites, labels, energies = spot.centroidal_voronoi(16, iterations=4)
    assert len(sites) == 16 and labels.min() >= 0 and labels.max() == 15
    assert np.all(np.diff(energies) <= 1e-12 * energies[:-1]) and energies[-1] < energies[0], energies
    bad = trigeo.InvalidArgumentError
    for call in (lambda: spot.centroidal_voronoi(0), lambda: spot.centroidal_voronoi(10 ** 6),
                 lambda: spot.centroidal_voronoi(3, iterations=0), lambda: spot.centroidal_voronoi(3, start=[0, 1]),
                 lambda: spot.centroidal_voronoi(3, tolerance=-1)):
        with pytest.raises(bad):
            call()
    with pytest.raises(KeyError):
        spot.centroidal_voronoi(16, progress=lambda fraction: (_ for _ in ()).throw(KeyError("stop")))
