"""Isolines of curve fields (Mesh.isolines(curve=, curves=, boundary=)): the offset curves of a
flat square's boundary are squares and those of a segment its stadium (Euclidean oracles, 1e-12);
on a curved mesh every point's field_at() from the same curve is its level; the same numbers as
the CLI's field --from boundary / curve:FILE --isolines and --isoline-count (and curve rows in
--sources FILE), bit for bit; bad input."""
import json

import numpy as np
import pytest

import trigeo
from conftest import SPOT, corpus, flat_grid, run_cli, seg_dist


def test_flat_squares_and_stadium():
    m = flat_grid(10)
    levels = [0.123, 0.0417, 0.3319]
    out = m.isolines(levels=levels, boundary=True, details=True)
    for level, lines in zip(levels, out):
        assert len(lines) == 1 and lines[0]["closed"], (level, len(lines))
        p = lines[0]["points"]
        near = np.minimum(np.minimum(p[:, 0], 1 - p[:, 0]), np.minimum(p[:, 1], 1 - p[:, 1]))
        assert np.abs(near - level).max() <= 1e-12, (level, np.abs(near - level).max())
        # straight sides meeting at the corners: the perimeter exact
        per = np.linalg.norm(np.diff(p, axis=0), axis=1).sum()
        assert abs(per - 4 * (1 - 2 * level)) <= 1e-12, (level, per)
    # a segment along the grid line x = 0.5 (vertices), y from 0.2 to 0.7: two straight sides and
    # two half circles
    line = [5 * 11 + k for k in range(2, 8)]
    a, b = np.array([0.5, 0.2, 0]), np.array([0.5, 0.7, 0])
    for level, lines in zip([0.13, 0.071], m.isolines(None, [0.13, 0.071], curve=line, threads=2)):
        assert len(lines) == 1 and np.array_equal(lines[0][0], lines[0][-1])
        assert np.abs(seg_dist(lines[0], a, b) - level).max() <= 1e-12


def test_curved_points_on_levels():
    m = trigeo.load(corpus("igl_camelhead.off"))
    d = m.field(boundary=True)
    far = d[np.isfinite(d)].max()
    levels = [far * k / 6 for k in range(1, 6)]
    out = m.isolines(levels=levels, boundary=True, details=True)
    assert all(len(lines) > 0 for lines in out)
    pts = [q for lines in out for pl in lines for q in pl["surface_points"]]
    want = np.array([lv for lv, lines in zip(levels, out) for pl in lines for _ in pl["surface_points"]])
    got = m.field_at(None, pts, boundary=True)
    diag = np.linalg.norm(m.vertices.max(0) - m.vertices.min(0))
    assert np.abs(got - want).max() <= 1e-12 * diag, np.abs(got - want).max() / diag


def cli_lines(path, count):
    doc = json.loads(path.read_text())
    return doc["levels"], [[np.array(pl["points"]) for pl in doc["polylines"] if pl["level"] == i]
                           for i in range(count)]


def test_equals_cli(tmp_path):
    name = corpus("igl_camelhead.off")
    m = trigeo.load(name)
    out = tmp_path / "iso.json"
    for opt, value, kw in (("--isolines", "0.05,0.21", {"levels": [0.05, 0.21]}), ("--isoline-count", "3",
                                                                                   {"count": 3})):
        r = run_cli("field", name, "--from", "boundary", opt, value, "-o", str(out), "--quiet")
        assert r.returncode == 0, r.stderr
        lines = m.isolines(boundary=True, **kw)
        levels, cli = cli_lines(out, len(lines))
        assert len(levels) == len(lines) and [len(x) for x in cli] == [len(x) for x in lines], opt
        assert sum(len(x) for x in lines) > 0
        for a, b in zip(cli, lines):
            for p, q in zip(a, b):
                assert np.array_equal(p, q), opt
    # curve rows in --sources FILE: the isolines of the nearest row, as the --from list's
    rows = tmp_path / "rows.txt"
    rows.write_text("boundary\nv:3\n")
    r = run_cli("field", name, "--sources", str(rows), "--isolines", "0.05,0.21", "-o", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    lines = m.isolines([3], [0.05, 0.21], boundary=True)
    _, cli = cli_lines(out, 2)
    assert [len(x) for x in cli] == [len(x) for x in lines]
    for a, b in zip(cli, lines):
        for p, q in zip(a, b):
            assert np.array_equal(p, q)
    # a path written as .obj is a curve for the CLI, its points one for Python; with a point source
    s = trigeo.load(SPOT)
    p = s.path(17, 2500)
    obj = tmp_path / "p.obj"
    r = run_cli("path", SPOT, "--from", "v:17", "--to", "v:2500", "-o", str(obj))
    assert r.returncode == 0, r.stderr
    r = run_cli("field", SPOT, "--from", f"curve:{obj};v:3", "--isolines", "0.1,0.3", "-o", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    lines = s.isolines([3], [0.1, 0.3], curve=p.points)
    _, cli = cli_lines(out, 2)
    assert [len(x) for x in cli] == [len(x) for x in lines] and len(lines[0]) > 0
    for a, b in zip(cli, lines):
        for u, w in zip(a, b):
            assert np.array_equal(u, w)


def test_bad_input(tmp_path):
    s = trigeo.load(SPOT)
    with pytest.raises(trigeo.InvalidArgumentError, match="needs sources"):
        s.isolines(levels=[0.1])
    with pytest.raises(trigeo.InvalidArgumentError, match="no boundary"):
        s.isolines(levels=[0.1], boundary=True)
    with pytest.raises(trigeo.InvalidArgumentError, match="no face together"):
        s.isolines(levels=[0.1], curve=[0, 2000])
    out = tmp_path / "iso.obj"
    r = run_cli("field", SPOT, "--from", "boundary", "--isolines", "0.1", "-o", str(out))
    assert r.returncode == 2 and "no boundary" in r.stderr and not out.exists(), r.stderr
    bad = tmp_path / "c.txt"
    bad.write_text("v:0\nv:2000\n")
    r = run_cli("field", SPOT, "--from", f"curve:{bad}", "--isolines", "0.1", "-o", str(out))
    assert r.returncode == 2 and f"{bad}:2:" in r.stderr and not out.exists(), r.stderr
    r = run_cli("field", SPOT, "--from", f"curve:{bad}", "--gradient", "-o", str(tmp_path / "g.npy"))
    assert r.returncode == 1 and "curve sources" in r.stderr
