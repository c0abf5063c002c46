"""Mesh.voronoi and Mesh.farthest_point_sampling against independent oracles: the argmin over
distance_matrix rows (ties to the lowest index, as numpy's argmin), the brute-force farthest-point
loop over Mesh.field, and the CLI (`trigeo sample`, `trigeo field --labels`) bit for bit."""
import numpy as np
import pytest

import trigeo
from conftest import SPOT, corpus, run_cli


@pytest.mark.parametrize("path", [SPOT, "cgal_elephant-with-holes.off"])
def test_voronoi_is_argmin_of_fields(path):
    m = trigeo.load(path if path == SPOT else corpus(path))
    rng = np.random.default_rng(3)
    src = [int(v) for v in rng.integers(0, m.vertex_count, 9)]
    src += [trigeo.SurfacePoint.face(5, (0.2, 0.3, 0.5)), src[2]]  # a face point; a repeat (empty cell)
    labels, dist = m.voronoi(src)
    M = m.distance_matrix(src)
    reached = np.isfinite(M).any(axis=0)
    assert np.array_equal(labels[reached], M.argmin(axis=0)[reached])
    assert np.array_equal(dist, M.min(axis=0))
    assert not (labels == len(src) - 1).any()


def test_two_components_and_limit():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [5, 0, 0], [6, 0, 0], [5, 1, 0]], float)
    m = trigeo.Mesh(v, np.array([[0, 1, 2], [3, 4, 5]]))
    labels, dist = m.voronoi([0, 1])
    assert list(labels) == [0, 1, 0, -1, -1, -1] and np.isinf(dist[3:]).all()
    labels, dist = m.voronoi([0], max_distance=0.5)
    assert list(labels) == [0, -1, -1, -1, -1, -1]
    samples, dist, labels = m.farthest_point_sampling(3, start=0)
    assert list(samples) == [0, 3, 1]  # +inf (the other component) is farthest; then the lowest index
    assert labels[4] == 1 and dist[0] == 0


def test_fps_equals_brute_force():
    m = trigeo.load(SPOT)
    k = 25
    samples, dist, labels = m.farthest_point_sampling(k, start=11)
    want, best = [11], np.full(m.vertex_count, np.inf)
    fields = []
    for i in range(k):
        f = m.field(want[i])
        fields.append(f)
        best = np.minimum(best, f)
        if i + 1 < k:
            cand = best.copy()
            cand[want] = -1
            want.append(int(np.argmax(cand)))
    assert list(samples) == want
    assert np.array_equal(dist, best)
    assert np.array_equal(labels, np.argmin(np.array(fields), axis=0))


def test_fps_and_labels_equal_cli(tmp_path):
    m = trigeo.load(SPOT)
    samples, dist, labels = m.farthest_point_sampling(12, seed=5)
    out, fld = tmp_path / "s.txt", tmp_path / "f.csv"
    r = run_cli("sample", SPOT, "--count", "12", "--seed", "5", "-o", str(out), "--field", str(fld))
    assert r.returncode == 0, r.stderr
    assert [int(s[2:]) for s in out.read_text().split()] == list(samples)
    cli = np.loadtxt(fld, delimiter=",", skiprows=1)
    assert np.array_equal(cli[:, 1].astype(np.int64), labels) and np.array_equal(cli[:, 2], dist)
    lab = tmp_path / "l.csv"
    r = run_cli("field", SPOT, "--sources", str(out), "--labels", "-o", str(lab))
    assert r.returncode == 0, r.stderr
    cli = np.loadtxt(lab, delimiter=",", skiprows=1)
    vl, vd = m.voronoi(list(samples))
    assert np.array_equal(cli[:, 1].astype(np.int64), vl) and np.array_equal(cli[:, 2], vd)
    assert np.array_equal(vl, labels) and np.array_equal(vd, dist)


def test_bad_input(tmp_path):
    m = trigeo.load(SPOT)
    for bad in [dict(count=0), dict(count=m.vertex_count + 1), dict(count=2, start=m.vertex_count),
                dict(count=2, start=-1), dict(count=1.5)]:
        with pytest.raises(trigeo.InvalidArgumentError):
            m.farthest_point_sampling(**bad)
    with pytest.raises(trigeo.InvalidArgumentError):
        m.voronoi([m.vertex_count])
    # the messages name the one cause: too many samples (with the number of vertices there are),
    # or a start no face uses (a mesh with a lone vertex)
    with pytest.raises(trigeo.InvalidArgumentError, match=r"^count 2931 exceeds the 2930 vertices used by faces$"):
        m.farthest_point_sampling(2931)
    lone = trigeo.Mesh(np.vstack([m.vertices, [[9.0, 9.0, 9.0]]]), m.faces)
    with pytest.raises(trigeo.InvalidArgumentError, match=r"^start 2930 is used by no face$"):
        lone.farthest_point_sampling(5000, start=2930)
    with pytest.raises(trigeo.InvalidArgumentError, match=r"^count 2931 exceeds the 2930 vertices used by faces$"):
        lone.farthest_point_sampling(2931, start=0)
    out = tmp_path / "s.txt"
    r = run_cli("sample", SPOT, "--count", str(m.vertex_count + 1), "-o", str(out))
    assert r.returncode == 2 and "--count" in r.stderr and not out.exists()
    r = run_cli("sample", SPOT, "--count", "0")
    assert r.returncode == 1
    r = run_cli("field", SPOT, "--from", "v:1;v:2", "--labels", "-o", str(tmp_path / "x.npy"))
    assert r.returncode == 1 and not (tmp_path / "x.npy").exists()


def test_boundaries_equidistant_and_render(tmp_path):
    m = trigeo.load(SPOT)
    src = [3, 700, 1500, 2200, trigeo.SurfacePoint.face(40, (0.5, 0.25, 0.25))]
    labels, dist, lines = m.voronoi(src, boundaries=True)
    assert np.array_equal(labels, m.voronoi(src)[0])
    assert lines and all(a < b for a, b in (ln["cells"] for ln in lines))
    for ln in lines:
        a, b = ln["cells"]
        edge = [p for p in ln["surface_points"] if p.kind == "edge"]
        da, db = m.field_at(src[a], edge), m.field_at(src[b], edge)
        assert np.all(np.abs(da - db) <= 1e-9 * np.maximum(da, db))
        assert ln["points"].shape == (len(ln["surface_points"]), 3)
    png = tmp_path / "v.png"
    m.render(png, labels=labels, boundaries=lines, width=64, height=48)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(trigeo.InvalidArgumentError):
        m.render(png, labels=labels[:-1])
