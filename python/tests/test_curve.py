"""Fields from curves (Mesh.field(curve=, curves=, boundary=), field_at, boundary_segments): on a
flat grid the Euclidean distance to the polyline and to the square's sides; the same numbers as
the CLI's --from curve:FILE / boundary, bit for bit; a path's points as a curve; bad input."""
import numpy as np
import pytest

import trigeo
from conftest import SPOT, corpus, flat_grid, run_cli, seg_dist


def test_flat_boundary_and_edges():
    m = flat_grid(10)
    v = m.vertices
    d = m.field(boundary=True)
    want = np.minimum(np.minimum(v[:, 0], 1 - v[:, 0]), np.minimum(v[:, 1], 1 - v[:, 1]))
    assert np.abs(d - want).max() <= 1e-12, np.abs(d - want).max()
    assert m.boundary_segments().shape == (40, 2)
    # a grid line x = 0.5 from y = 0.2 to 0.7 along the edges, as vertices: the distance to the segment
    line = [5 * 11 + k for k in range(2, 8)]
    d = m.field(curve=line, threads=2)
    a, b = np.array([0.5, 0.2, 0]), np.array([0.5, 0.7, 0])
    assert np.abs(d - seg_dist(v, a, b)).max() <= 1e-12
    # points: the same at face points, mixed with a point source far away
    rng = np.random.default_rng(5)
    q = np.column_stack([rng.uniform(0, 1, (50, 2)), np.zeros(50)])
    got = m.field_at([0], q, curve=line)
    want = np.minimum(seg_dist(q, a, b), np.linalg.norm(q, axis=1))
    assert np.abs(got - want).max() <= 1e-12, np.abs(got - want).max()


def test_equals_cli_and_path_curve(tmp_path):
    name = corpus("igl_camelhead.off")
    m = trigeo.load(name)
    out = tmp_path / "b.csv"
    r = run_cli("field", name, "--from", "boundary", "--csv", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    assert np.array_equal(np.loadtxt(out, delimiter=",", skiprows=1)[:, 1], m.field(boundary=True))
    # on 2 threads, and at points (--at, SPECs and x y z), mixed with a point source: the same bits
    r = run_cli("field", name, "--from", "boundary;v:100", "--threads", "2", "--csv", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    assert np.array_equal(np.loadtxt(out, delimiter=",", skiprows=1)[:, 1], m.field([100], boundary=True, threads=2))
    pts = tmp_path / "at.txt"
    xyz = m.vertices[[7, 4000]] * 0.5 + m.vertices[[8, 4001]] * 0.5
    pts.write_text("v:3\nf:10:0.2,0.3,0.5\n" + "".join("%.17g %.17g %.17g\n" % tuple(q) for q in xyz))
    at = tmp_path / "at.csv"
    r = run_cli("field", name, "--from", "boundary;v:100", "--at", str(pts), "-o", str(at), "--quiet")
    assert r.returncode == 0, r.stderr
    want = m.field_at([100], [3, trigeo.SurfacePoint(10, (0.2, 0.3, 0.5))] + list(xyz), boundary=True)
    assert np.array_equal(np.loadtxt(at), want)
    # a path written as .obj is a curve for the CLI; its points are one for Python: the same field
    s = trigeo.load(SPOT)
    p = s.path(17, 2500)
    obj = tmp_path / "p.obj"
    r = run_cli("path", SPOT, "--from", "v:17", "--to", "v:2500", "-o", str(obj))
    assert r.returncode == 0, r.stderr
    out = tmp_path / "c.csv"
    r = run_cli("field", SPOT, "--from", f"curve:{obj};v:3", "--csv", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    cli = np.loadtxt(out, delimiter=",", skiprows=1)[:, 1]
    assert np.array_equal(cli, s.field([3], curve=p.points))
    xyz = np.array([[float(t) for t in line.split()[1:]] for line in obj.read_text().splitlines()
                    if line.startswith("v ")])
    assert np.array_equal(cli, s.field(3, curve=xyz))
    # every point of the curve at distance 0 (to the rounding of a position), never below
    d = s.field_at(None, p.surface_points, curve=p.points)
    assert np.all(d >= 0.0) and d.max() <= 1e-15, d


def test_curve_paths(tmp_path):
    """curve_path: on the flat grid a straight path of the Euclidean distance to the boundary,
    starting on it; on nvd_spot of field_at's length from a path-curve and a point, and the CLI's
    path --from "curve:FILE;v:3" the same points."""
    m = flat_grid(10)
    rng = np.random.default_rng(2)
    for q in np.column_stack([rng.uniform(0.05, 0.95, (10, 2)), np.zeros(10)]):
        p = m.curve_path(q, boundary=True)
        want = min(q[0], 1 - q[0], q[1], 1 - q[1])
        assert p.global_ == "proven" and abs(p.length - want) <= 1e-12, (p.length, want)
        assert min(p.points[0][0], 1 - p.points[0][0], p.points[0][1], 1 - p.points[0][1]) <= 1e-12
        assert np.linalg.norm(p.points[-1] - q) <= 1e-12
    s = trigeo.load(SPOT)
    curve = s.path(17, 2500).points
    for v in (100, 900, 2000):
        p = s.curve_path(v, curve=curve, sources=[3])
        d = s.field_at([3], [v], curve=curve)[0]
        assert p.global_ == "proven" and abs(p.length - d) <= 1e-12 * d
    obj = tmp_path / "c.obj"
    r = run_cli("path", SPOT, "--from", "v:17", "--to", "v:2500", "-o", str(obj))
    assert r.returncode == 0, r.stderr
    out = tmp_path / "p.obj"
    r = run_cli("path", SPOT, "--from", f"curve:{obj};v:3", "--to", "v:900", "-o", str(out))
    assert r.returncode == 0, r.stderr
    cli = np.array([[float(t) for t in line.split()[1:]] for line in out.read_text().splitlines()
                    if line.startswith("v ")])
    py = s.curve_path(900, curve=curve, sources=[3]).points
    assert cli.shape == py.shape and np.abs(cli - py).max() <= 1e-15
    with pytest.raises(trigeo.InvalidArgumentError, match="needs curve"):
        s.curve_path(900)


def test_curve_voronoi(tmp_path):
    """voronoi(curves=, boundary=): on the flat grid the Euclidean argmin over a point, a curve
    and the boundary; the CLI's --labels with the same sites in the list's order the same."""
    m = flat_grid(12)
    v = m.vertices
    line = [6 * 13 + k for k in range(3, 10)]  # x = 0.5, y = 0.25 .. 0.75
    lab, d = m.voronoi([13 * 2 + 2], curves=[line], boundary=True)
    a, b = np.array([0.5, 0.25, 0]), np.array([0.5, 0.75, 0])
    e = np.stack([np.linalg.norm(v - v[13 * 2 + 2], axis=1), seg_dist(v, a, b),
                  np.minimum(np.minimum(v[:, 0], 1 - v[:, 0]), np.minimum(v[:, 1], 1 - v[:, 1]))])
    srt = np.sort(e, axis=0)
    clear = srt[1] - srt[0] > 1e-9
    assert np.array_equal(lab[clear], e.argmin(0)[clear]) and np.abs(d - srt[0]).max() <= 1e-12
    name = corpus("igl_camelhead.off")
    c = trigeo.load(name)
    e = [int(i) for i in c.faces[0][:2]]  # an edge of the mesh
    curve = tmp_path / "c.txt"
    curve.write_text(f"v:{e[0]}\nv:{e[1]}\n")
    out = tmp_path / "l.csv"
    r = run_cli("field", name, "--from", f"v:5000;curve:{curve};boundary", "--labels", "-o", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    cli = np.loadtxt(out, delimiter=",", skiprows=1)
    lab, d = c.voronoi([5000], curves=[e], boundary=True)
    assert np.array_equal(cli[:, 1].astype(np.int64), lab) and np.array_equal(cli[:, 2], d)


def test_curve_matrix(tmp_path):
    """distance_matrix(curves=, boundary=): each row its own field bit for bit (and at targets);
    the CLI's --sources with curve:FILE and boundary lines the same rows."""
    name = corpus("igl_camelhead.off")
    c = trigeo.load(name)
    e = [int(i) for i in c.faces[0][:2]]
    path = c.path(10, 8000).points
    m = c.distance_matrix([5000], curves=[e, path], boundary=True, threads=2)
    assert m.shape == (4, c.vertex_count)
    assert np.array_equal(m[0], c.field([5000]))
    assert np.array_equal(m[1], c.field(curve=e)) and np.array_equal(m[2], c.field(curve=path))
    assert np.array_equal(m[3], c.field(boundary=True))
    at = c.distance_matrix([5000], curves=[e], targets=[1, 2, 3])
    assert np.array_equal(at[1], c.field_at(None, [1, 2, 3], curve=e))
    curve = tmp_path / "e.txt"
    curve.write_text(f"v:{e[0]}\nv:{e[1]}\n")
    rows = tmp_path / "rows.txt"
    rows.write_text(f"boundary\nv:5000\ncurve:{curve}\n")
    out = tmp_path / "m.npy"
    r = run_cli("field", name, "--sources", str(rows), "-o", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    cli = np.load(out)
    assert np.array_equal(cli, m[[3, 0, 1]])


def test_bad_curves(tmp_path):
    s = trigeo.load(SPOT)
    with pytest.raises(trigeo.InvalidArgumentError, match="no face together"):
        s.field(curve=[0, 2000])
    with pytest.raises(trigeo.InvalidArgumentError, match="no boundary"):
        s.field(boundary=True)
    with pytest.raises(trigeo.InvalidArgumentError, match="needs sources"):
        s.field()
    with pytest.raises(trigeo.InvalidArgumentError, match="list of polylines"):
        s.field(curves=5)
    bad = tmp_path / "c.txt"
    bad.write_text("v:0\nv:2000\n")
    r = run_cli("field", SPOT, "--from", f"curve:{bad}", "-o", str(tmp_path / "o.ply"))
    assert r.returncode == 2 and f"{bad}:2: the segment from line 1" in r.stderr, r.stderr
    assert not (tmp_path / "o.ply").exists()
    r = run_cli("field", SPOT, "--from", "boundary", "-o", str(tmp_path / "o.ply"))
    assert r.returncode == 2 and "no boundary" in r.stderr
    r = run_cli("field", SPOT, "--from", f"curve:{bad}", "--gradient", "-o", str(tmp_path / "o.npy"))
    assert r.returncode == 1 and "curve sources" in r.stderr
    # the output may not overwrite the curve file
    r = run_cli("field", SPOT, "--from", f"curve:{bad}", "--csv", str(bad))
    assert r.returncode != 0 and bad.read_text() == "v:0\nv:2000\n"
