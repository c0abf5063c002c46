"""Mesh.log_map: the polar coordinates of a flat sheet (1e-12), distances equal to field()'s bit
for bit, tracing back along (r, theta) to the vertex, the checkerboard picture, and clear errors
for bad reference vectors and sources."""
import math

import numpy as np
import pytest

import trigeo
from conftest import SPOT, grid, run_cli


def flat_sheet(n=12):
    v, f = grid(n, amplitude=0.0)
    rng = np.random.default_rng(5)
    inner = (v[:, 0] > 0) & (v[:, 0] < n - 1) & (v[:, 1] > 0) & (v[:, 1] < n - 1)
    v[inner, :2] += rng.uniform(-0.3, 0.3, (inner.sum(), 2))
    return trigeo.Mesh(v, f)


def test_flat_log_map_is_polar_coordinates():
    m = flat_sheet()
    face = 40
    b = np.array([0.2, 0.3, 0.5])
    p0 = b @ m.vertices[m.faces[face]]
    r, theta, uv = m.log_map(trigeo.SurfacePoint.face(face, b), ref=(1.0, 0.0, 0.3))
    d = m.vertices[:, :2] - p0[:2]
    assert np.abs(r - np.hypot(d[:, 0], d[:, 1])).max() <= 1e-12 * 12
    assert np.abs(uv - d).max() <= 1e-12 * 12
    assert theta.min() >= 0 and theta.max() < 2 * math.pi
    # the default reference: from the face's corner 0 towards its corner 1
    e = m.vertices[m.faces[face][1]] - m.vertices[m.faces[face][0]]
    a0 = math.atan2(e[1], e[0])
    _, theta0, _ = m.log_map(trigeo.SurfacePoint.face(face, b))
    assert np.abs(np.angle(np.exp(1j * (theta0 + a0 - theta)))).max() <= 1e-12


def test_distances_are_the_field_and_traces_go_back():
    v, f = grid(14, amplitude=0.3)
    m = trigeo.Mesh(v, f)
    src = trigeo.SurfacePoint.face(77, (0.3, 0.3, 0.4))
    r, theta, _ = m.log_map(src)
    assert np.array_equal(r, m.field([src]))
    checked = 0
    for vtx in np.argsort(r)[-12:]:
        t = m.trace(src, float(theta[vtx]), float(r[vtx]))
        path = m.path(src, int(vtx))
        if any(p.kind == "vertex" for p in path.surface_points[1:-1]):
            continue  # a path bending at a vertex: the trace goes straight through it
        assert np.abs(t.end_xyz - m.vertices[vtx]).max() <= 1e-9 * 14
        checked += 1
    assert checked > 0


def test_render_checkerboard(tmp_path):
    m = flat_sheet()
    _, _, uv = m.log_map(5)
    out = tmp_path / "lm.png"
    m.render(out, logmap=uv, checker=0.5, view=(0, 0, -1), width=64, height=48)
    assert out.stat().st_size > 0
    with pytest.raises(trigeo.InvalidArgumentError):
        m.render(out, logmap=uv[:3])


def test_bad_input():
    m = flat_sheet()
    for ref in [(0, 0, 0), (math.nan, 1, 0), (0, 0, 1), (1, 2)]:
        with pytest.raises(trigeo.InvalidArgumentError):
            m.log_map(3, ref=ref)
    with pytest.raises(trigeo.InvalidArgumentError):
        m.log_map(10 ** 6)
    r, theta, uv = m.log_map(3, max_distance=1.0)
    far = r == math.inf
    assert far.any() and np.all(theta[far] == 0) and np.all(uv[far] == math.inf) and not np.isnan(theta).any()


def test_transport_is_the_identity_on_a_plane_and_follows_the_paths():
    """Mesh.transport_field and Path.transport: on a jittered flat sheet every vertex (and every
    point of a path) gets the vector's projection with its length; on a curved mesh the field at a
    vertex equals the transport along that vertex's own exact path (two computations); the CLI's
    logmap --transport gives the same numbers; bad vectors raise."""
    m = flat_sheet()
    src = trigeo.SurfacePoint.face(40, (0.2, 0.3, 0.5))
    vec = np.array([0.6, -0.8, 0.0])
    out, dist, flag = m.transport_field(src, (0.6, -0.8, 0.0))
    assert np.all(flag == 0)
    assert np.abs(out - vec).max() <= 1e-12 and np.array_equal(dist, m.log_map(src)[0])
    p = m.path(src, 100)
    tilted = np.array([0.6, -0.8, 0.7])
    t = p.transport(tilted)
    assert t.shape == (len(p), 3)
    assert np.abs(t - vec * np.linalg.norm(tilted)).max() <= 1e-12
    spot = trigeo.load(SPOT)
    s = trigeo.SurfacePoint.face(100, (0.2, 0.3, 0.5))
    field, _, _ = spot.transport_field(s, (0.3, 1.0, -0.2), threads=2)
    for v in (7, 400, 1200, 2500):
        last = spot.path(s, v).transport((0.3, 1.0, -0.2))[-1]
        assert np.abs(last - field[v]).max() <= 1e-9, (v, last, field[v])
    for bad in ((0, 0, 0), (1, 2), (math.nan, 0, 1)):
        with pytest.raises(trigeo.InvalidArgumentError, match="vector"):
            spot.transport_field(s, bad)
        with pytest.raises(trigeo.InvalidArgumentError, match="vector"):
            p.transport(bad)
    with pytest.raises(trigeo.InvalidArgumentError, match="perpendicular"):
        m.transport_field(src, (0.0, 0.0, 1.0))


def test_cli_logmap_transport_columns(tmp_path):
    spot = trigeo.load(SPOT)
    out = tmp_path / "t.npy"
    r = run_cli("logmap", SPOT, "--from", "v:3", "--transport", "1,2,0.5", "-o", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    a = np.load(out)
    vec, dist, flag = spot.transport_field(3, (1.0, 2.0, 0.5))
    assert a.shape == (spot.vertex_count, 8) and np.array_equal(a[:, 4:7], vec) and np.array_equal(a[:, 0], dist)
    assert np.array_equal(a[:, 7], flag)


def test_field_gradient_on_a_plane_and_the_cli(tmp_path):
    """Mesh.field_gradient: on a jittered flat sheet the vertex and face gradients are
    (x - nearest source) / distance (1e-12), labels the nearest source, sources flagged; the CLI's
    field --gradient writes the same numbers; bad arguments raise."""
    m = flat_sheet()
    s0, s1 = trigeo.SurfacePoint.face(40, (0.2, 0.3, 0.5)), trigeo.SurfacePoint.vertex(100)
    p0 = np.array([0.2, 0.3, 0.5]) @ m.vertices[m.faces[40]]
    p1 = m.vertices[100]
    g = m.field_gradient([s0, s1], faces=True, threads=2)
    d0 = np.linalg.norm(m.vertices - p0, axis=1)
    d1 = np.linalg.norm(m.vertices - p1, axis=1)
    near = np.where(d0 <= d1, 0, 1)
    ok = g["flag"] == 0
    assert g["flag"][100] == 1 and ok.sum() >= m.vertex_count - 2
    assert np.array_equal(g["label"][ok], near[ok])
    sp = np.where(near[:, None] == 0, p0, p1)
    with np.errstate(invalid="ignore"):  # 0 / 0 at the source vertex (flagged, not compared)
        want = (m.vertices - sp) / np.minimum(d0, d1)[:, None]
    assert np.abs(g["gradient"][ok] - want[ok]).max() <= 1e-12
    c = m.vertices[m.faces].mean(axis=1)
    c0, c1 = np.linalg.norm(c - p0, axis=1), np.linalg.norm(c - p1, axis=1)
    fs = np.where((c0 <= c1)[:, None], p0, p1)
    assert np.all(g["face_flag"] == 0)
    assert np.abs(g["face_gradient"] - (c - fs) / np.minimum(c0, c1)[:, None]).max() <= 1e-12
    spot = trigeo.load(SPOT)
    one = spot.field_gradient([0, 1500])
    out = tmp_path / "g.npy"
    r = run_cli("field", SPOT, "--from", "v:0;v:1500", "--gradient", "-o", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    a = np.load(out)
    assert a.shape == (spot.vertex_count, 6) and np.array_equal(a[:, 0], one["distance"])
    assert np.array_equal(a[:, 1:4], one["gradient"]) and np.array_equal(a[:, 4], one["flag"])
    assert np.array_equal(a[:, 5], one["label"])
    for bad in ({"faces": 2}, {"threads": -1}, {"max_distance": -1.0}):
        with pytest.raises(trigeo.InvalidArgumentError):
            spot.field_gradient(0, **bad)
