"""Mesh.distance_to: the certified distance between two meshes against answers known by hand (a
grid moved by a known vector), a brute-force scan (every face of B, NumPy), the CLI's JSON (the
same numbers bit for bit), and bad arguments."""
import json
import math

import numpy as np
import pytest

import trigeo
from conftest import corpus, run_cli


def flat_grid(n, shift=(0.0, 0.0, 0.0)):
    xs = np.linspace(0.0, 1.0, n + 1)
    v = np.array([(x + shift[0], y + shift[1], shift[2]) for y in xs for x in xs])
    f = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 1, a + n + 2
            f += [(a, b, d), (a, d, c)] if (i + j) % 2 == 0 else [(a, b, c), (b, d, c)]
    return trigeo.Mesh(v, np.array(f))


def test_grid_moved_along_its_normal():
    h = 0.0217
    a, b = flat_grid(8), flat_grid(8, (0, 0, h))
    r = a.distance_to(b, tolerance=1e-12)
    assert r.lower <= h <= r.upper and r.upper - r.lower <= r.tolerance, (r.lower, h, r.upper, r.tolerance)
    assert r.converged
    assert r.mean[0] <= h <= r.mean[1] and r.rms[0] <= h <= r.rms[1], (r.mean, r.rms)
    assert np.all(np.abs(r.vertex_distance - h) <= 1e-15), r.vertex_distance[:4]
    assert abs(r.area - 1.0) <= 1e-14


def test_grid_moved_by_a_vector_symmetric():
    t = (0.031, 0.012, 0.02)
    a, b = flat_grid(6), flat_grid(7, t)
    r = a.distance_to(b, symmetric=True, tolerance=1e-12)
    exact = math.sqrt(sum(x * x for x in t))  # A's corner (0, 0) and B's corner (1, 1) + t
    for d in (r, r.reverse):
        assert d.lower <= exact <= d.upper and d.upper - d.lower <= d.tolerance, (d.lower, exact, d.upper)
    assert r.symmetric == (max(r.lower, r.reverse.lower), max(r.upper, r.reverse.upper))
    assert np.allclose(r.point[:2], (0, 0), atol=1e-15) and np.allclose(r.reverse.point[:2], (1 + t[0], 1 + t[1]))


def scan(points, b):
    """Distance from each point to the mesh b by every face (NumPy, no BVH): the minimum over
    faces of the distance to the triangle, from the projection clamped into it by its edges."""
    V, F = np.array(b.vertices), np.array(b.faces)
    best = np.full(len(points), np.inf)
    for f in F:
        best = np.minimum(best, points_triangle(points, *V[f]))
    return best


def points_triangle(P, a, b, c):
    """Distances from the rows of P to triangle abc: inside the prism the plane distance, else the
    nearest of the three edges (segments)."""
    n = np.cross(b - a, c - a)
    n = n / np.linalg.norm(n)
    d_plane = (P - a) @ n
    Q = P - np.outer(d_plane, n)
    def inside(u, v, w):
        return np.cross(v - u, Q - u) @ n >= 0
    ins = inside(a, b, c) & inside(b, c, a) & inside(c, a, b)
    def seg(u, v):
        e = v - u
        t = np.clip((P - u) @ e / (e @ e), 0, 1)
        return np.linalg.norm(P - (u + np.outer(t, e)), axis=1)
    edge = np.minimum(np.minimum(seg(a, b), seg(b, c)), seg(c, a))
    return np.where(ins, np.abs(d_plane), edge)


def sphere(n_lat, n_lon, r):
    v = [(0, 0, r), (0, 0, -r)]
    for i in range(1, n_lat):
        th = math.pi * i / n_lat
        for j in range(n_lon):
            ph = 2 * math.pi * (j + 0.37 * i) / n_lon
            v.append((r * math.sin(th) * math.cos(ph), r * math.sin(th) * math.sin(ph), r * math.cos(th)))
    idx = lambda i, j: 2 + (i - 1) * n_lon + j % n_lon
    f = [(0, idx(1, j), idx(1, j + 1)) for j in range(n_lon)]
    for i in range(1, n_lat - 1):
        for j in range(n_lon):
            f += [(idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)), (idx(i, j), idx(i + 1, j + 1), idx(i, j + 1))]
    f += [(1, idx(n_lat - 1, j + 1), idx(n_lat - 1, j)) for j in range(n_lon)]
    return trigeo.Mesh(np.array(v, float), np.array(f))


def test_against_sampling():
    """A sampled maximum (what MeshLab and libigl report) is only a lower bound: the certified
    interval is above it within the tolerance, and the scan at the realising point agrees."""
    a, b = sphere(9, 13, 1.0), sphere(7, 11, 1.4)
    r = a.distance_to(b, tolerance=1e-9, threads=1)
    rng = np.random.default_rng(3)
    V, F = np.array(a.vertices), np.array(a.faces)
    w = rng.dirichlet((1, 1, 1), size=(len(F), 40))
    P = np.einsum("fkc,fcd->fkd", w, V[F]).reshape(-1, 3)
    sampled = scan(P, b).max()
    assert r.lower >= sampled - r.tolerance and r.upper >= sampled, (r.lower, sampled, r.upper)
    assert abs(scan(np.array([r.point]), b)[0] - r.distance) <= 1e-12
    assert np.allclose(r.vertex_distance, scan(V, b), rtol=0, atol=1e-12)
    assert a.distance_to(b, tolerance=1e-9, threads=2).as_dict() == r.as_dict()


def test_equals_cli():
    pa, pb = corpus("cgal_elephant.off"), corpus("igl_decimated-knight.off")
    a, b = trigeo.load(pa), trigeo.load(pb)
    r = a.distance_to(b, symmetric=True, mean_tolerance=5e-3)
    out = run_cli("compare", pa, pb, "--symmetric", "--json", "--mean-tolerance", "5e-3")
    assert out.returncode == 0, out.stderr
    j = json.loads(out.stdout)
    assert r.as_dict() == j["a_to_b"] and r.reverse.as_dict() == j["b_to_a"]
    assert list(r.symmetric) == [j["symmetric"]["lower"], j["symmetric"]["upper"]]


def test_bad_arguments():
    a, b = flat_grid(2), flat_grid(3, (0, 0, 1))
    for t in (float("nan"), -1.0, 0.0, float("inf"), "1"):
        with pytest.raises(trigeo.InvalidArgumentError):
            a.distance_to(b, tolerance=t)
        with pytest.raises(trigeo.InvalidArgumentError):
            a.distance_to(b, mean_tolerance=t)
    for bad in (None, "b.obj", np.zeros((3, 3))):
        with pytest.raises(trigeo.InvalidArgumentError):
            a.distance_to(bad)
    with pytest.raises(trigeo.InvalidArgumentError):
        a.distance_to(b, threads=-1)
    empty = trigeo.Mesh(np.zeros((3, 3)), np.zeros((0, 3), dtype=np.uint32))
    with pytest.raises(trigeo.InvalidArgumentError, match="no faces"):
        empty.distance_to(b)
    with pytest.raises(trigeo.InvalidArgumentError, match="no faces"):
        a.distance_to(empty)
    with pytest.raises(trigeo.CancelledError):
        a.distance_to(b, progress=lambda f: False)
