"""Mesh.trace, Mesh.trace_batch and Mesh.path_through against known answers: straight lines on a
flat sheet (1e-12), helices on a prism (the unrolled line), a belt around a cube, the exact path
back from a trace's end never longer than the trace, routes equal to the sum of their exact
pieces, and clear errors for bad directions, lengths and points."""
import math

import numpy as np
import pytest

import trigeo
from conftest import grid


def flat_sheet(n=12):
    v, f = grid(n, amplitude=0.0)
    rng = np.random.default_rng(3)
    inner = (v[:, 0] > 0) & (v[:, 0] < n - 1) & (v[:, 1] > 0) & (v[:, 1] < n - 1)
    v[inner, :2] += rng.uniform(-0.3, 0.3, (inner.sum(), 2))
    return trigeo.Mesh(v, f)


def test_flat_trace_is_the_straight_line():
    m = flat_sheet()
    rng = np.random.default_rng(7)
    for _ in range(40):
        face = int(rng.integers(m.face_count))
        b = rng.dirichlet((2, 2, 2))
        start = trigeo.SurfacePoint.face(face, b)
        p0 = b @ m.vertices[m.faces[face]]
        ang = rng.uniform(0, 2 * math.pi)
        d = np.array([math.cos(ang), math.sin(ang), 0.0])
        length = rng.uniform(0, 3)
        t = m.trace(start, d * 2.5 + [0, 0, 0.7], length)  # the normal part is projected away
        if t.status == "boundary":
            assert t.length < length
            want = p0 + t.length * d
        else:
            assert t.status == "complete" and t.length == length
            want = p0 + length * d
        assert np.abs(t.end_xyz - want).max() <= 1e-12
        assert np.abs(t.end_direction - d).max() <= 1e-12
        # every point of the polyline lies on the segment
        s = (t.points - p0) @ d
        assert np.abs(t.points - (p0 + s[:, None] * d)).max() <= 1e-12
        assert np.all(np.diff(s) >= -1e-12)
        assert len(t.faces) == len(t) - 1 and np.abs(t.points[0] - p0).max() <= 1e-14


def prism(n=24, rings=40, height=10.0):
    """An open regular n-gon prism of circumradius 1 (the polygonal cylinder), rings of height
    height / rings."""
    k = np.arange(n)
    v = np.concatenate([np.stack([np.cos(2 * math.pi * k / n), np.sin(2 * math.pi * k / n),
                                  np.full(n, height * r / rings)], 1) for r in range(rings + 1)])
    f = []
    for r in range(rings):
        for i in range(n):
            a, b = r * n + i, r * n + (i + 1) % n
            f += [(a, b, b + n), (a, b + n, a + n)]
    return trigeo.Mesh(v, np.array(f))


def perimeter_u(p, n, side):
    """The unrolled coordinate of p round the prism: the distance along the polygon from vertex 0."""
    k = int(math.floor((math.atan2(p[1], p[0]) % (2 * math.pi)) / (2 * math.pi / n) + 1e-12)) % n
    c = np.array([math.cos(2 * math.pi * k / n), math.sin(2 * math.pi * k / n)])
    return k * side + float(np.linalg.norm(p[:2] - c))


def test_prism_traces_are_helices():
    """Unrolled, the prism is a strip of width n * side: a geodesic is a straight line of it, so
    it rises by L sin(a) while going round L cos(a) of the perimeter."""
    n = 24
    m = prism(n)
    side = 2 * math.sin(math.pi / n)
    for a in (0.1, 0.35, 0.8, 1.2):
        # from the middle of an edge on the ring at height 1, along the ring's direction (edge 0->1)
        # tilted up by a: at the middle of a face the direction is known without unrolling
        p0 = (m.vertices[n * 4] + m.vertices[n * 4 + 1]) / 2
        along = (m.vertices[n * 4 + 1] - m.vertices[n * 4]) / side
        start = m.locate(p0)  # the edge point
        length = 3.0 * n * side  # three times round
        d = math.cos(a) * along + math.sin(a) * np.array([0, 0, 1.0])
        t = m.trace(start, d, min(length, 4.0 / math.sin(a)))
        assert t.status == "complete"
        z = t.points[:, 2]
        # height is linear in the distance walked, the pitch tan(a) per unit of perimeter
        walked = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(t.points, axis=0), axis=1))])
        assert np.abs(z - (p0[2] + walked * math.sin(a))).max() <= 1e-11
        assert abs(walked[-1] - t.length) <= 1e-11
        # round the axis, the end is L cos(a) further along the perimeter (modulo the perimeter)
        u_end = perimeter_u(t.end_xyz, n, side)
        want = (0.5 * side + t.length * math.cos(a)) % (n * side)
        assert min(abs(u_end - want), n * side - abs(u_end - want)) <= 1e-11
        assert abs(t.end_direction[2] - math.sin(a)) <= 1e-12


def cube():
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    f = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    return trigeo.Mesh(v, np.array(f))


def test_cube_belt_and_known_geodesic():
    m = cube()
    # round the belt z = 0.3 from the face x = 0: length 4 comes back to the start, same direction
    start = m.locate((0.0, 0.4, 0.3))
    t = m.trace(start, (0, 1, 0), 4.0)
    assert t.status == "complete"
    assert np.abs(t.end_xyz - [0, 0.4, 0.3]).max() <= 1e-12
    assert np.abs(t.end_direction - [0, 1, 0]).max() <= 1e-12
    assert np.abs(t.points[:, 2] - 0.3).max() <= 1e-15
    # a 45-degree line: from (0, 0.5, 0.2) on x = 0 going (0, 1, 1)/sqrt 2 meets the edge y = 1 at
    # z = 0.7, crosses onto y = 1 going (1, 0, 1)/sqrt 2 and meets the top z = 1 at x = 0.3
    t = m.trace(m.locate((0, 0.5, 0.2)), (0, 1, 1), math.sqrt(2) * 0.8)
    assert np.abs(t.end_xyz - [0.3, 1, 1]).max() <= 1e-12
    assert np.abs(t.end_direction - np.array([1, 0, 1]) / math.sqrt(2)).max() <= 1e-12 or \
        np.abs(t.end_direction - np.array([1, -1, 0]) / math.sqrt(2)).max() <= 1e-12


def test_path_back_never_longer_than_the_trace(spot):
    rng = np.random.default_rng(11)
    diag = float(np.linalg.norm(spot.vertices.max(0) - spot.vertices.min(0)))
    k = 30
    starts = [trigeo.SurfacePoint.face(int(rng.integers(spot.face_count)), rng.dirichlet((1, 1, 1))) for _ in range(k)]
    dirs = rng.normal(size=(k, 3))
    lengths = rng.uniform(0, 0.5 * diag, k)
    ends = spot.trace_batch(starts, dirs, lengths, threads=2)
    for i in range(k):
        t = spot.trace(starts[i], dirs[i], lengths[i])
        # the batch is bit for bit the single trace
        assert t.status == ends["status"][i] and t.length == ends["length"][i]
        assert np.array_equal(t.end_xyz, ends["xyz"][i]) and np.array_equal(t.end_direction, ends["direction"][i])
        assert t.end == ends["points"][i] and t.end_face == ends["face"][i] and t.crossings == ends["crossings"][i]
        back = spot.path(t.end, starts[i])
        assert back.proven and back.length <= t.length * (1 + 1e-12) + 1e-12 * diag


def test_trace_batch_angles_equal_single_traces(spot):
    ends = spot.trace_batch([0, 5, 9], [0.2, 2.0, -1.0], 0.3, angles=True)
    for i, (v, a) in enumerate(zip([0, 5, 9], [0.2, 2.0, -1.0])):
        t = spot.trace(v, a, 0.3)
        assert np.array_equal(t.end_xyz, ends["xyz"][i])
    empty = spot.trace_batch([], np.empty((0, 3)), [])
    assert empty["xyz"].shape == (0, 3) and empty["status"].shape == (0,)


def test_path_through_is_the_sum_of_exact_paths(spot):
    pts = [0, trigeo.SurfacePoint.face(900, (0.2, 0.3, 0.5)), 2000, trigeo.SurfacePoint.edge(3 * 40 + 1, 0.25)]
    for closed in (False, True):
        route = spot.path_through(pts, closed=closed)
        seq = pts + ([pts[0]] if closed else [])
        pieces = [spot.path(seq[i], seq[i + 1]) for i in range(len(seq) - 1)]
        assert route.proven and route.status == "converged"
        assert route.length == pytest.approx(sum(p.length for p in pieces), rel=1e-15)
        wp = route.waypoint_points
        assert len(wp) == len(seq) and wp[0] == 0 and wp[-1] == len(route) - 1
        for i, p in enumerate(pieces):
            assert np.array_equal(route.points[wp[i]:wp[i + 1] + 1], p.points)
    one = spot.path_through([7])
    assert one.length == 0 and len(one) == 2 and list(one.waypoint_points) == [0]
    loop = spot.path_through([7], closed=True)
    assert loop.length == 0 and list(loop.waypoint_points) == [0, 1]
    assert spot.path(0, 1).waypoint_points is None


def test_errors(spot):
    bad = trigeo.InvalidArgumentError
    for direction in [(0, 0, 0), (math.nan, 0, 0), (1, 0), "up", math.inf]:
        with pytest.raises(bad):
            spot.trace(0, direction, 1.0)
    for length in [-1.0, math.nan, math.inf]:
        with pytest.raises(bad, match="length"):
            spot.trace(0, (1, 0, 0), length)
    with pytest.raises(bad, match="out of range"):
        spot.trace(10 ** 6, (1, 0, 0), 1.0)
    n = np.cross(*(spot.vertices[spot.faces[5, 1:]] - spot.vertices[spot.faces[5, 0]]))
    with pytest.raises(bad, match="perpendicular"):
        spot.trace(trigeo.SurfacePoint.face(5, (0.2, 0.3, 0.5)), n, 1.0)
    with pytest.raises(bad, match=r"direction\[1\] is perpendicular"):
        spot.trace_batch([trigeo.SurfacePoint.face(4, (0.2, 0.3, 0.5)), trigeo.SurfacePoint.face(5, (0.2, 0.3, 0.5))],
                         [(1, 0, 0), n], 1.0)
    with pytest.raises(bad, match="lengths"):
        spot.trace_batch([0, 1], (1, 0, 0), [1.0, 2.0, 3.0])
    with pytest.raises(bad, match="length"):
        spot.trace_batch([0, 1], (1, 0, 0), [1.0, -2.0])
    with pytest.raises(bad):
        spot.path_through([])
    with pytest.raises(bad, match="not a vertex"):
        spot.path_through([0, 10 ** 6])
