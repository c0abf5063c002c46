"""The Python results equal the CLI's, bit for bit (the CLI prints %.17g), on corpus meshes."""
import os

import numpy as np
import pytest

import trigeo
from conftest import SPOT, corpus, run_cli

MESHES = ["nvd_spot", "igl_decimated-knight.off", "cgal_elephant-with-holes.off", "c3d_suzanne.obj",
          "tm_soup.stl", "gc_moebius.obj"]


def mesh_path(name):
    return SPOT if name == "nvd_spot" else corpus(name)


@pytest.mark.parametrize("name", MESHES)
def test_closest_equals_cli(name, tmp_path):
    path = mesh_path(name)
    m = trigeo.load(path)
    rng = np.random.default_rng(7)
    lo, hi = np.array(m.report["bbox_min"]), np.array(m.report["bbox_max"])
    q = rng.uniform(lo - 0.1 * (hi - lo), hi + 0.1 * (hi - lo), size=(200, 3))
    qf = tmp_path / "q.txt"
    np.savetxt(qf, q, fmt="%.17g")
    out = tmp_path / "c.csv"
    r = run_cli("closest", path, str(qf), "--signed", "-o", str(out))
    assert r.returncode == 0, r.stderr
    cli = np.loadtxt(out, delimiter=",", skiprows=1)
    d, face, p = m.closest(q)
    assert np.array_equal(face, cli[:, 1].astype(np.int64))
    assert np.array_equal(d, np.sqrt(cli[:, 2]))
    assert np.array_equal(p, cli[:, 3:6])
    s, _, _ = m.signed_distance(q)
    assert np.array_equal(np.sign(s), cli[:, 9])


@pytest.mark.parametrize("name", MESHES)
@pytest.mark.parametrize("method", ["straighten", "exact", None])  # None: both sides' default (exact)
def test_path_lengths_equal_cli(name, method, tmp_path):
    path = mesh_path(name)
    m = trigeo.load(path)
    rng = np.random.default_rng(3)
    used = np.unique(m.faces)
    pairs = rng.choice(used, size=(12, 2))
    pf = tmp_path / "pairs.txt"
    pf.write_text("".join(f"v {a} {b}\n" for a, b in pairs))
    out = tmp_path / "p.csv"
    r = run_cli("path", path, "--pairs", str(pf), *(["--method", method] if method else []), "-o", str(out))
    assert r.returncode == 0, r.stderr
    rows = [line.split(",") for line in out.read_text().splitlines()[1:]]
    cli = np.array([float(row[1]) for row in rows])
    kw = {"method": method} if method else {}
    got = m.path_lengths(pairs, threads=2, **kw)
    assert np.array_equal(got, cli)
    for i in (0, 5):
        p = m.path(int(pairs[i, 0]), int(pairs[i, 1]), **kw)
        assert p.length == cli[i] and p.global_ == rows[i][6] and p.status == rows[i][3]
        if method is None and p.status == "converged":
            assert p.global_ == "proven"


@pytest.mark.parametrize("name", MESHES)
def test_field_equals_cli(name, tmp_path):
    path = mesh_path(name)
    m = trigeo.load(path)
    src = int(np.unique(m.faces)[len(np.unique(m.faces)) // 3])
    out = tmp_path / "f.npy"
    r = run_cli("field", path, "--from", f"v:{src};f:0:0.2,0.3,0.5", "-o", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    got = m.field([trigeo.SurfacePoint.vertex(src), trigeo.SurfacePoint(0, (0.2, 0.3, 0.5))])
    assert np.array_equal(got, np.load(out))


def test_distance_matrix_equals_cli(tmp_path):
    m = trigeo.load(SPOT)
    sf = tmp_path / "s.txt"
    sf.write_text("v:0\nv:1500\nf:10:0.2,0.3,0.5\n")
    out = tmp_path / "m.npy"
    r = run_cli("field", SPOT, "--sources", str(sf), "-o", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    got = m.distance_matrix([0, 1500, trigeo.SurfacePoint(10, (0.2, 0.3, 0.5))], threads=2)
    assert got.shape == (3, m.vertex_count) and np.array_equal(got, np.load(out))
    assert np.array_equal(got[1], m.field(1500))


def test_field_at_equals_cli(tmp_path):
    m = trigeo.load(SPOT)
    pts = np.array([[0.1, 0.2, 0.3], [0.0, 0.5, -0.2], [0.3, -0.3, 0.8]])
    pf = tmp_path / "at.txt"
    np.savetxt(pf, pts, fmt="%.17g")
    out = tmp_path / "at.txt.out"
    r = run_cli("field", SPOT, "--from", "v:0", "--at", str(pf), "--quiet")
    assert r.returncode == 0, r.stderr
    cli = np.array([float(x) for x in r.stdout.split()])
    assert np.array_equal(m.field_at(0, pts), cli)
