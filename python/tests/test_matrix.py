"""Distance matrices as users ask other libraries for them: the sparse local matrix (every vertex
within a radius, scipy.sparse.csr_matrix), the matrix between sources and selected points, through
Python and the CLI (.npz read back by scipy, .csv triplets). Known answers and checks after
tvb-gdist's own tests (its flat 11 x 11 grid of spacing 0.2; a spiky closed "hedgehog" mesh;
local matrices with and without a radius; selected points), with the sparse path as the subject
and the dense full fields as the oracle."""
import math
import os

import numpy as np
import pytest

import trigeo
from conftest import SPOT, run_cli

scipy_sparse = pytest.importorskip("scipy.sparse")


def flat_grid(n=11, h=0.2):
    """tvb-gdist's flat mesh: n x n vertices of spacing h, vertex v at (h (v % n), h (v // n), 0)."""
    xy = np.array([(h * (v % n), h * (v // n), 0.0) for v in range(n * n)])
    faces = []
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            faces += [(a, a + 1, a + n + 1), (a, a + n + 1, a + n)]
    return trigeo.Mesh(xy, np.array(faces))


def hedgehog(level=2, spikes=24, height=0.6, seed=3):
    """A closed spiky surface: an icosahedron subdivided `level` times onto the unit sphere, with
    `spikes` vertices pushed outwards (saddle and spike vertices: pseudo-sources everywhere)."""
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
         (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    v = [np.array(p, float) / np.linalg.norm(p) for p in v]
    for _ in range(level):
        mid = {}

        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                p = v[a] + v[b]
                v.append(p / np.linalg.norm(p))
                mid[k] = len(v) - 1
            return mid[k]

        f = [g for a, b, c in f for g in ((a, m(a, b), m(c, a)), (b, m(b, c), m(a, b)), (c, m(c, a), m(b, c)),
                                          (m(a, b), m(b, c), m(c, a)))]
    v = np.array(v)
    rng = np.random.default_rng(seed)
    v[rng.choice(len(v), spikes, replace=False)] *= 1 + height
    return trigeo.Mesh(v, np.array(f))


def dense_oracle(mesh, sources, radius=None):
    """Each row a full field (no radius: the sparse rows must equal its entries within it)."""
    return np.array([mesh.field([s]) for s in sources])


def check_sparse_equals_fields(mesh, sources, radius):
    m = mesh.distance_matrix(sources, max_distance=radius, sparse=True, threads=2)
    assert isinstance(m, scipy_sparse.csr_matrix)
    assert m.shape == (len(sources), mesh.vertex_count) and m.has_sorted_indices
    full = dense_oracle(mesh, sources)
    r = math.inf if radius is None else radius
    for i in range(len(sources)):
        lo, hi = m.indptr[i], m.indptr[i + 1]
        cols, vals = m.indices[lo:hi], m.data[lo:hi]
        within = np.flatnonzero(full[i] <= r)
        assert np.array_equal(cols, within), f"row {i}: stored columns differ from the field's within {r}"
        assert np.array_equal(vals, full[i][within]), f"row {i}: values differ from the field's (bit for bit)"
    return m


def test_flat_mesh_known_answers():
    mesh = flat_grid()
    n = mesh.vertex_count
    xy = mesh.vertices[:, :2]
    euclid = np.linalg.norm(xy[:, None, :] - xy[None, :, :], axis=2)
    # the local matrix without a radius: every pair, the plane's distances
    m = check_sparse_equals_fields(mesh, list(range(n)), None)
    assert m.nnz == n * n
    d = m.toarray()
    assert np.allclose(d, euclid, rtol=1e-13, atol=1e-15)
    np.testing.assert_array_almost_equal(d[1][0:10], [0.2, 0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6])
    assert (abs(m - m.T) > 1e-6).nnz == 0  # tvb-gdist's symmetry check
    # with a radius (0.5 is no grid distance: no pair sits on it)
    m = mesh.distance_matrix("all", max_distance=0.5, sparse=True)
    assert m.nnz == int((euclid <= 0.5).sum())
    assert np.allclose(m.toarray()[euclid <= 0.5], euclid[euclid <= 0.5], rtol=1e-13, atol=1e-15)
    # selected points, and tvb-gdist's max_distance check
    pts = [2, 5, 10]
    s = mesh.distance_matrix(pts, targets=pts)
    assert np.allclose(s, euclid[np.ix_(pts, pts)], rtol=1e-13, atol=1e-15) and np.allclose(s, s.T, atol=1e-6)
    lim = mesh.distance_matrix(pts, targets=pts, max_distance=0.4)
    assert np.array_equal(np.isinf(lim), euclid[np.ix_(pts, pts)] > 0.4) and not (lim[np.isfinite(lim)] > 0.4).any()


def test_hedgehog_sparse_equals_fields():
    mesh = hedgehog()
    sources = list(range(0, mesh.vertex_count, 7)) + [trigeo.SurfacePoint(10, (0.2, 0.3, 0.5))]
    for radius in (None, 0.3, 0.0):
        check_sparse_equals_fields(mesh, sources, radius)
    everything = mesh.distance_matrix("all", max_distance=0.6, sparse=True, threads=2)
    assert everything.nnz < 0.5 * mesh.vertex_count ** 2  # tvb-gdist: sparse enough
    both = everything.multiply(everything.T > 0)  # pairs stored both ways
    diff = abs(both - both.T).max()
    assert diff <= 1e-12 * everything.max(), f"asymmetry {diff}"
    sym = everything.maximum(everything.T)
    assert (abs(sym - sym.T) > 0).nnz == 0


def test_selected_points_equal_full_fields():
    mesh = trigeo.load(SPOT)
    rng = np.random.default_rng(5)
    sources = [int(i) for i in rng.integers(0, mesh.vertex_count, 5)] + [trigeo.SurfacePoint(7, (0.1, 0.6, 0.3))]
    verts = [int(i) for i in rng.integers(0, mesh.vertex_count, 9)]
    targets = verts + [trigeo.SurfacePoint(100, (0.3, 0.3, 0.4)), trigeo.SurfacePoint.edge(61, 0.4)]
    got = mesh.distance_matrix(sources, targets=targets, threads=2)
    assert got.shape == (len(sources), len(targets))
    full = dense_oracle(mesh, sources)
    assert np.array_equal(got[:, :len(verts)], full[:, verts])
    for i, s in enumerate(sources):
        # the face and edge points: field_at with the vertex field also asked (never stopped early)
        assert np.array_equal(got[i, len(verts):], mesh.field_at([s], targets[len(verts):]))
    with pytest.raises(trigeo.InvalidArgumentError):
        mesh.distance_matrix([0], targets=[mesh.vertex_count])
    with pytest.raises(trigeo.InvalidArgumentError):
        mesh.distance_matrix([0], max_distance=-1.0, sparse=True)
    with pytest.raises(trigeo.InvalidArgumentError):
        mesh.distance_matrix([0], max_distance=float("nan"), sparse=True)
    with pytest.raises(trigeo.InvalidArgumentError):
        mesh.distance_matrix("some", max_distance=1.0, sparse=True)
    # "all" without sparse=True is refused naming sparse=True (not as a string read as points)
    with pytest.raises(trigeo.InvalidArgumentError, match="sparse=True"):
        mesh.distance_matrix("all", max_distance=1.0)


def test_cli_npz_csv_and_points(tmp_path):
    mesh = trigeo.load(SPOT)
    src = tmp_path / "sources.txt"
    src.write_text("# sources\nv:0\nv:10\nf:3:0.2,0.3,0.5\n")
    npz, csv = tmp_path / "m.npz", tmp_path / "m.csv"
    r = run_cli("field", SPOT, "--sources", str(src), "--max-distance", "0.3", "-o", str(npz), "--threads", "2")
    assert r.returncode == 0, r.stderr
    want = mesh.distance_matrix([0, 10, trigeo.SurfacePoint(3, (0.2, 0.3, 0.5))], max_distance=0.3, sparse=True)
    got = scipy_sparse.load_npz(str(npz))
    assert got.shape == want.shape and np.array_equal(got.indptr, want.indptr)
    assert np.array_equal(got.indices, want.indices) and np.array_equal(got.data, want.data)
    r = run_cli("field", SPOT, "--sources", str(src), "--max-distance", "0.3", "--sparse", "-o", str(csv))
    assert r.returncode == 0, r.stderr
    lines = csv.read_text().splitlines()
    assert lines[0] == "i,j,d" and len(lines) == want.nnz + 1
    t = np.array([[float(x) for x in line.split(",")] for line in lines[1:]])
    coo = want.tocoo()
    assert np.array_equal(t[:, 0], coo.row) and np.array_equal(t[:, 1], coo.col) and np.array_equal(t[:, 2], coo.data)
    # every vertex
    r = run_cli("field", SPOT, "--sources", "all", "--max-distance", "0.05", "-o", str(npz))
    assert r.returncode == 0, r.stderr
    got = scipy_sparse.load_npz(str(npz))
    want = mesh.distance_matrix("all", max_distance=0.05, sparse=True)
    assert (got != want).nnz == 0 and np.array_equal(got.data, want.data)
    # selected points
    to = tmp_path / "to.txt"
    to.write_text("v:5\nf:100:0.3,0.3,0.4\n0.1 0.2 0.3\n")
    npy = tmp_path / "k.npy"
    r = run_cli("field", SPOT, "--sources", str(src), "--to", str(to), "-o", str(npy))
    assert r.returncode == 0, r.stderr
    k = np.load(npy)
    want = mesh.distance_matrix([0, 10, trigeo.SurfacePoint(3, (0.2, 0.3, 0.5))],
                                targets=[5, trigeo.SurfacePoint(100, (0.3, 0.3, 0.4)), (0.1, 0.2, 0.3)])
    assert np.array_equal(k, want)


@pytest.mark.parametrize("case", ["bad_source", "bad_target", "negative", "nan", "all_dense"])
def test_cli_bad_input_leaves_no_file(tmp_path, case):
    src, to = tmp_path / "s.txt", tmp_path / "t.txt"
    src.write_text("v:0\nv:%d\n" % (10 ** 6 if case == "bad_source" else 1))
    to.write_text("v:2\nnot a point\n")
    out = tmp_path / ("m.npy" if case in ("bad_target", "all_dense") else "m.npz")
    args = {"bad_source": ["--sources", str(src), "--max-distance", "0.1"],
            "bad_target": ["--sources", str(src), "--to", str(to)],
            "negative": ["--sources", str(src), "--max-distance", "-0.5"],
            "nan": ["--sources", str(src), "--max-distance", "nan"],
            "all_dense": ["--sources", "all"]}[case]
    r = run_cli("field", SPOT, *args, "-o", str(out))
    expect = {"bad_source": (2, f"{src}:2:"), "bad_target": (2, f"{to}:2:"), "negative": (1, "--max-distance"),
              "nan": (1, "--max-distance"), "all_dense": (1, ".npz")}[case]
    assert r.returncode == expect[0] and expect[1] in r.stderr, r.stderr
    assert sorted(os.listdir(tmp_path)) == ["s.txt", "t.txt"]
