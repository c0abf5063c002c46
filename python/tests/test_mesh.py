"""Meshes, arrays and the closest-point family: shapes, dtypes, zero copy, independent checks."""
import gc
import math

import numpy as np
import pytest

import trigeo
from conftest import SPOT, corpus


def test_load_and_report(spot):
    assert spot.vertex_count == 2930 and spot.face_count == 5856
    r = spot.report
    assert r["closed_manifold"] is True and r["genus"] == 0 and r["components"] == 1
    assert r["vertices"] == 2930 and r["edges"] == 8784 and len(r["bbox_min"]) == 3
    assert spot.source.endswith("nvd_spot.obj")
    assert "2930 vertices" in repr(spot)


def test_views_are_zero_copy_and_read_only(spot):
    v, f = spot.vertices, spot.faces
    assert v.shape == (2930, 3) and v.dtype == np.float64 and f.shape == (5856, 3) and f.dtype == np.uint32
    assert np.shares_memory(v, spot.vertices) and np.shares_memory(f, spot.faces)  # the library's arrays
    assert not v.flags.writeable and not f.flags.writeable
    with pytest.raises(ValueError):
        v[0, 0] = 1.0


def test_views_outlive_close():
    m = trigeo.load(SPOT)
    v = m.vertices
    first = v[:3].copy()
    m.close()
    with pytest.raises(trigeo.InvalidArgumentError, match="closed"):
        m.closest([0.0, 0.0, 0.0])
    del m
    gc.collect()
    assert np.array_equal(v[:3], first)  # still the library's memory, kept alive by the view


def test_arrays_round_trip(spot):
    m = trigeo.Mesh(spot.vertices, spot.faces)
    assert m.source is None
    assert np.array_equal(m.vertices, spot.vertices) and np.array_equal(m.faces, spot.faces)
    # int64 faces and float32 vertices are converted (a copy), results unchanged for exact floats
    m2 = trigeo.Mesh(np.array(spot.vertices, dtype=np.float64), spot.faces.astype(np.int64))
    assert np.array_equal(m2.faces, spot.faces)
    assert m.report == {**spot.report}


def test_points_zero_copy():
    a = np.zeros((5, 3))
    assert trigeo._points(a) is a  # C-contiguous float64 goes to the library as it is
    b = np.zeros((5, 3), dtype=np.float32)
    assert trigeo._points(b) is not b and trigeo._points(b).dtype == np.float64
    assert trigeo._points(np.asfortranarray(np.zeros((5, 3)))).flags.c_contiguous


def brute_closest(v, f, q):
    """Closest distance by dense sampling of every face: an upper bound independent of the kernel."""
    best = np.full(len(q), np.inf)
    n = 24
    us = [(i / n, j / n) for i in range(n + 1) for j in range(n + 1 - i)]
    tri = v[f.astype(np.int64)]
    for (a, b) in us:
        pts = tri[:, 0] * (1 - a - b) + tri[:, 1] * a + tri[:, 2] * b
        for k in range(len(q)):
            best[k] = min(best[k], np.min(np.linalg.norm(pts - q[k], axis=1)))
    return best


def test_closest_shapes_and_independent_check(spot):
    rng = np.random.default_rng(1)
    lo, hi = np.array(spot.report["bbox_min"]), np.array(spot.report["bbox_max"])
    q = rng.uniform(lo - 0.2, hi + 0.2, size=(40, 3))
    d, face, p = spot.closest(q)
    assert d.shape == (40,) and face.shape == (40,) and p.shape == (40, 3)
    assert d.dtype == np.float64 and face.dtype == np.int64 and p.dtype == np.float64
    assert np.allclose(np.linalg.norm(p - q, axis=1), d, rtol=1e-12, atol=1e-15)
    # never farther than any sample of any face, and the sampling is dense enough to come close
    ub = brute_closest(spot.vertices, spot.faces, q)
    assert np.all(d <= ub * (1 + 1e-12))
    assert np.all(ub - d < 0.02)
    # the closest point lies in its face's plane, inside the face
    v = spot.vertices
    tri = v[spot.faces[face].astype(np.int64)]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    assert np.allclose(np.einsum("ij,ij->i", p - tri[:, 0], n / np.linalg.norm(n, axis=1)[:, None]), 0, atol=1e-12)
    # threads do not change a bit; one point as (3,) works
    d1, f1, p1 = spot.closest(q, threads=1)
    assert np.array_equal(d, d1) and np.array_equal(face, f1) and np.array_equal(p, p1)
    d0, f0, p0 = spot.closest(q[7])
    assert d0.shape == (1,) and d0[0] == d[7] and f0[0] == face[7]


def test_signed_and_winding(spot):
    q = np.array([[0.0, 0.0, 0.0], [5.0, 5.0, 5.0], [0.2, 0.1, 0.5]])
    for method in ("auto", "pseudonormal", "winding"):
        s, face, p = spot.signed_distance(q, method=method)
        d, f2, p2 = spot.closest(q)
        assert np.array_equal(np.abs(s), d) and np.array_equal(face, f2)
        assert s[0] < 0 and s[1] > 0
    w = spot.winding_number(q)
    assert w.shape == (3,) and abs(w[0] - 1) < 1e-2 and abs(w[1]) < 1e-2
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.signed_distance(q, method="parity")


def test_empty_mesh():
    m = trigeo.Mesh(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.uint32))
    d, f, p = m.closest([[1.0, 2.0, 3.0]])
    assert d[0] == math.inf and f[0] == -1
    assert m.closest(np.zeros((0, 3)))[0].shape == (0,)
    with pytest.raises(trigeo.InvalidArgumentError, match="no faces"):
        m.field([(0.0, 0.0, 0.0)])


def test_gz_and_other_formats():
    m = trigeo.load(corpus("openfoam_terrain.stl.gz"))
    assert m.face_count > 0
    m = trigeo.load(corpus("c3d_horse.ply"))
    assert m.report["faces"] == m.face_count


def test_save_round_trip(spot, tmp_path):
    d = spot.field(0)
    ply, obj = tmp_path / "spot.ply", tmp_path / "spot.obj"
    spot.save(ply, fields={"distance": d, "height": spot.vertices[:, 1]})
    spot.save(obj)
    for p in (ply, obj):
        m = trigeo.load(p)
        assert np.array_equal(m.vertices, spot.vertices) and np.array_equal(m.faces, spot.faces)
    # the field reads back through the CLI's renderer path (tg_ply_read_vertex_scalar)
    from conftest import run_cli
    r = run_cli("render", str(ply), "--field", str(ply), "--scalar", "distance", "-o", str(tmp_path / "f.png"))
    assert r.returncode == 0, r.stderr
    raw = ply.read_bytes()
    assert b"property double distance" in raw and b"property double height" in raw
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.save(tmp_path / "a.stl")
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.save(obj, fields={"distance": d})
    for bad in ("bad name", "x", ""):
        with pytest.raises(trigeo.InvalidArgumentError):
            spot.save(ply, fields={bad: d})
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.save(ply, fields={"d": d[:5]})
    with pytest.raises(trigeo.FileError):
        spot.save(tmp_path / "no" / "dir" / "x.ply")
