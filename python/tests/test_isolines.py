"""Mesh.isolines against independent oracles: field_at() at the returned surface points (the
level, 1e-9 relative), circles about a source on a flat square, the CLI's JSON (`trigeo field
--isolines`) point for point, and bad levels."""
import json
import math

import numpy as np
import pytest

import trigeo
from conftest import SPOT, corpus, run_cli


def flat_square(n=12):
    xs = np.linspace(0.0, 1.0, n + 1)
    v = np.array([[x, y, 0.0] for y in xs for x in xs])
    f = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            f += [[a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]]
    return trigeo.Mesh(v, np.array(f))


def test_flat_circles():
    m = flat_square()
    src = trigeo.SurfacePoint.face(100, (0.2, 0.3, 0.5))
    c = m.field_at([src], [src])  # the source's own distance: 0
    assert c[0] == 0.0
    centre = m.vertices[m.faces[100]].T @ np.array([0.2, 0.3, 0.5])
    out = m.isolines([src], [0.1, 0.15])
    assert len(out) == 2
    for level, lines in zip([0.1, 0.15], out):
        assert len(lines) == 1
        r = np.linalg.norm(lines[0][:, :2] - centre[:2], axis=1)
        assert np.max(np.abs(r - level)) <= 1e-12
        assert np.array_equal(lines[0][0], lines[0][-1])  # closed: the first point repeated


@pytest.mark.parametrize("path", [SPOT, "cgal_elephant-with-holes.off"])
def test_points_on_levels(path):
    m = trigeo.load(path if path == SPOT else corpus(path))
    src = [0, m.vertex_count // 2, trigeo.SurfacePoint.face(7, (0.6, 0.2, 0.2))]
    far = np.max(m.field(src)[np.isfinite(m.field(src))])
    levels = [far * k / 7 for k in range(1, 7)]
    out = m.isolines(src, levels, details=True)
    assert [len(x) > 0 for x in out] == [True] * 6
    pts = [p for lines in out for pl in lines for p in pl["surface_points"]]
    want = np.array([lv for lv, lines in zip(levels, out) for pl in lines for _ in pl["surface_points"]])
    got = m.field_at(src, pts)
    assert np.max(np.abs(got - want) / want) <= 1e-9


def test_equals_cli(tmp_path):
    out = tmp_path / "iso.json"
    run_cli("field", SPOT, "--from", "v:5", "--isolines", "0.2,0.4", "-o", str(out), "--quiet")
    doc = json.loads(out.read_text())
    lines = trigeo.load(SPOT).isolines(5, [0.2, 0.4])
    cli = [[np.array(pl["points"]) for pl in doc["polylines"] if pl["level"] == i] for i in range(2)]
    assert [len(x) for x in cli] == [len(x) for x in lines]
    for a, b in zip(cli, lines):
        for p, q in zip(a, b):
            assert np.array_equal(p, q)


def test_one_rule_with_the_cli(tmp_path):
    """A number is always a level (3 is the level 3, in Python as in the CLI's --isolines 3); a
    count of levels is asked for by name: count=N equals the CLI's --isoline-count N, levels and
    points bit for bit."""
    m = trigeo.load(SPOT)
    assert [len(x) for x in m.isolines(5, 0.3)] == [len(x) for x in m.isolines(5, [0.3])]
    for opt, value, kw in (("--isolines", "0.3", {"levels": 0.3}), ("--isoline-count", "3", {"count": 3})):
        out = tmp_path / "iso.json"
        r = run_cli("field", SPOT, "--from", "v:5", opt, value, "-o", str(out), "--quiet")
        assert r.returncode == 0, r.stderr
        doc = json.loads(out.read_text())
        lines = m.isolines(5, **kw)
        assert len(doc["levels"]) == len(lines), (opt, doc["levels"])
        cli = [[np.array(pl["points"]) for pl in doc["polylines"] if pl["level"] == i] for i in range(len(lines))]
        assert [len(x) for x in cli] == [len(x) for x in lines], opt
        for a, b in zip(cli, lines):
            for p, q in zip(a, b):
                assert np.array_equal(p, q), opt
    # count=N: max * k / (N + 1) of the field's largest finite distance
    d = m.field(5)
    far = d[np.isfinite(d)].max()
    got = m.isolines(5, count=3, details=True)
    for k, lines in enumerate(got):
        want = far * (k + 1) / 4
        for pl in lines:
            at = m.field_at(5, pl["surface_points"])
            assert np.all(np.abs(at - want) <= 1e-9 * want), (k, at[:3], want)


def test_bad_levels():
    m = flat_square(4)
    for bad in ([], [-0.1], [math.nan], [math.inf], [0.1, -1.0]):
        with pytest.raises(trigeo.InvalidArgumentError):
            m.isolines(0, bad)
    for bad in (0, -1, 4097, 2.5, True, "3"):
        with pytest.raises(trigeo.InvalidArgumentError, match="count"):
            m.isolines(0, count=bad)
    with pytest.raises(trigeo.InvalidArgumentError, match="one of them"):
        m.isolines(0, [0.1], count=2)
    with pytest.raises(trigeo.InvalidArgumentError, match="one of them"):
        m.isolines(0)
    # no sources: nothing reached, no curves (the one rule for empty source lists)
    assert m.isolines([], [0.1, 0.2]) == [[], []]


def test_render_draws_them(tmp_path):
    m = trigeo.load(SPOT)
    d = m.field(0)
    levels = [0.2, 0.4, 0.6]
    bands, lines = tmp_path / "bands.png", tmp_path / "lines.png"
    m.render(bands, field=d, width=120, height=90)
    m.render(lines, field=d, width=120, height=90, isolines=m.isolines(0, levels), isoline_levels=levels)
    assert bands.read_bytes() != lines.read_bytes()
