"""Numbers, one rule in Python and the CLI: a number is the double it is (subnormals included),
then checked against its argument's range (finite; >= 0 where a length, distance, level or
radius is meant). Every numeric argument of the Python package, and the CLI option that takes
the same number, over the values 0, 5e-324, 1e-320, -0.0, -5e-324, inf, nan and 1e308: the
rule's verdict in Python, and Python's verdict = the CLI's. The issue: --max-distance 4.9e-324,
--length 1e-320 and --dir 1e-320,0,0 were refused with false reasons while Python took
max_distance=5e-324."""
import math

import numpy as np
import pytest

import trigeo
from conftest import grid, run_cli

VALUES = [0.0, 5e-324, 1e-320, -0.0, -5e-324, math.inf, math.nan, 1e308]
V = 27  # an interior vertex of the 8 x 8 grid
F, H = 30, 91  # a face and a halfedge inside it


def _rule(allowed, x):
    """The verdict of the rule: True when x is in the argument's range."""
    if allowed == "finite":
        return math.isfinite(x)
    if allowed == ">=0":
        return math.isfinite(x) and x >= 0.0
    if allowed == ">0":
        return math.isfinite(x) and x > 0.0
    if allowed == "coordinate":  # a position: finite, within the library's +-1e150
        return math.isfinite(x) and abs(x) <= 1e150
    raise AssertionError(allowed)


@pytest.fixture(scope="module")
def setup(tmp_path_factory):
    d = tmp_path_factory.mktemp("numbers")
    v, f = grid(8)
    mesh_path = str(d / "grid.obj")
    trigeo.Mesh(v, f).save(mesh_path)
    m = trigeo.load(mesh_path)
    r = run_cli("logmap", mesh_path, "--from", f"v:{V}", "-o", str(d / "lm.ply"), "--quiet")
    assert r.returncode == 0, r.stderr
    uv = m.log_map(V)[2]
    return m, mesh_path, str(d / "lm.ply"), uv, d


# (the argument, its range, the Python call, the CLI arguments for the same number as text s;
#  the name the Python message gives, or None where the library judges the value)
ROWS = [
    ("max_distance", ">=0", lambda m, x, e: m.field(0, max_distance=x),
     lambda s, e: ["field", e.mesh, "--from", "v:0", "--max-distance", s, "-o", e.out("f.csv")], "max_distance"),
    ("trace length", ">=0", lambda m, x, e: m.trace(V, 0.0, x),
     lambda s, e: ["trace", e.mesh, "--from", f"v:{V}", "--angle", "0", "--length", s, "-o", e.out("t.obj")],
     "length"),
    ("trace angle", "finite", lambda m, x, e: m.trace(V, x, 0.5),
     lambda s, e: ["trace", e.mesh, "--from", f"v:{V}", "--angle", s, "--length", "0.5", "-o", e.out("t.obj")],
     "angle"),
    ("trace direction", "finite", lambda m, x, e: m.trace(V, (1.0, x, 0.0), 0.5),
     lambda s, e: ["trace", e.mesh, "--from", f"v:{V}", "--dir", f"1,{s},0", "--length", "0.5", "-o", e.out("t.obj")],
     "direction"),
    ("log map ref", "finite", lambda m, x, e: m.log_map(V, ref=(1.0, x, 0.0)),
     lambda s, e: ["logmap", e.mesh, "--from", f"v:{V}", "--ref", f"1,{s},0", "-o", e.out("l.csv"), "--quiet"], "ref"),
    ("log map max_distance", ">=0", lambda m, x, e: m.log_map(V, max_distance=x),
     lambda s, e: ["logmap", e.mesh, "--from", f"v:{V}", "--max-distance", s, "-o", e.out("l.csv"), "--quiet"],
     "max_distance"),
    ("isoline level", ">=0", lambda m, x, e: m.isolines(0, [0.25, x]),
     lambda s, e: ["field", e.mesh, "--from", "v:0", "--isolines", f"0.25,{s}", "-o", e.out("i.obj")], "levels"),
    ("render view", "finite", lambda m, x, e: m.render(e.out("v.png"), view=(1.0, x, 0.5), width=32, height=24),
     lambda s, e: ["render", e.mesh, "--view", f"1,{s},0.5", "--size", "32x24", "-o", e.out("v.png")], "view"),
    ("render checker", ">=0", lambda m, x, e: m.render(e.out("c.png"), logmap=e.uv, checker=x, width=32, height=24),
     lambda s, e: ["render", e.mesh, "--logmap", e.logmap, "--checker", s, "--size", "32x24", "-o", e.out("c.png")],
     "checker"),
    ("position coordinate", "coordinate", lambda m, x, e: m.field([(3.2, 3.4, x)]),
     lambda s, e: ["field", e.mesh, "--from", f"p:3.2,3.4,{s}", "-o", e.out("f.csv")], "sources"),
    ("closest query coordinate", "coordinate", lambda m, x, e: m.closest([(3.2, 3.4, x)]),
     lambda s, e: ["closest", e.mesh, e.write("q.txt", f"3.2 3.4 {s}\n"), "-o", e.out("c.csv")], "points"),
    ("batch length", ">=0", lambda m, x, e: m.trace_batch([V, V + 1], 0.0, [0.5, x], angles=True),
     lambda s, e: ["trace", e.mesh, "--batch", e.write("b.txt", f"v:{V} 0 0.5\nv:{V + 1} 0 {s}\n"), "-o",
                   e.out("b.csv")],
     "length"),
    ("batch angle", "finite", lambda m, x, e: m.trace_batch([V, V + 1], [0.0, x], 0.5, angles=True),
     lambda s, e: ["trace", e.mesh, "--batch", e.write("b.txt", f"v:{V} 0 0.5\nv:{V + 1} {s} 0.5\n"), "-o",
                   e.out("b.csv")],
     "angle"),
    ("batch direction", "finite", lambda m, x, e: m.trace_batch([V, V + 1], [(1.0, 0.0, 0.0), (1.0, x, 0.0)], 0.5),
     lambda s, e: ["trace", e.mesh, "--batch", e.write("b.txt", f"v:{V} 1,0,0 0.5\nv:{V + 1} 1,{s},0 0.5\n"), "-o",
                   e.out("b.csv")], "direction"),
    ("barycentric coordinate", None, lambda m, x, e: m.field(trigeo.SurfacePoint(F, (x, 0.5, 0.5))),
     lambda s, e: ["field", e.mesh, "--from", f"f:{F}:{s},0.5,0.5", "-o", e.out("f.csv")], None),
    ("edge parameter", None, lambda m, x, e: m.field(trigeo.SurfacePoint.edge(H, x)),
     lambda s, e: ["field", e.mesh, "--from", f"e:{H}:{s}", "-o", e.out("f.csv")], None),
]


class _Env:
    def __init__(self, setup, tmp_path):
        self.m, self.mesh, self.logmap, self.uv, _ = setup
        self.tmp = tmp_path

    def out(self, name):
        return str(self.tmp / name)

    def write(self, name, text):
        (self.tmp / name).write_text(text)
        return str(self.tmp / name)


def _python(row, x, env):
    """("ok" | "refused", the error) of the Python call."""
    try:
        row[2](env.m, x, env)
        return "ok", None
    except trigeo.Error as e:
        return "refused", e


def _number_refusal(err, name):
    return isinstance(err, trigeo.InvalidArgumentError) and name in str(err) and "must be" in str(err)


RANGED = [r for r in ROWS if r[1] is not None]  # the others the library judges against the mesh


@pytest.mark.parametrize("row", RANGED, ids=[r[0].replace(" ", "_") for r in RANGED])
def test_python_numbers_follow_the_rule(setup, tmp_path, row):
    name, allowed, _, _, arg = row
    env = _Env(setup, tmp_path)
    bad = []
    for x in VALUES:
        verdict, err = _python(row, x, env)
        if _rule(allowed, x):
            if verdict == "refused" and _number_refusal(err, arg):
                bad.append(f"{x!r}: refused as a number ({err}) though in range {allowed}")
        elif verdict == "ok" or not isinstance(err, trigeo.InvalidArgumentError) or arg not in str(err):
            bad.append(f"{x!r}: {verdict} ({err}), the rule refuses it ({allowed}) with a message naming {arg}")
    assert not bad, f"{name}:\n  " + "\n  ".join(bad)


@pytest.mark.parametrize("row", ROWS, ids=[r[0].replace(" ", "_") for r in ROWS])
def test_cli_and_python_agree(setup, tmp_path, row):
    """The same verdict on every value. render --checker: 0 and -0.0 are left out (Python's
    checker=0 is its documented default, the bounding box diagonal / 40; the CLI's default is to
    leave --checker out, and --checker takes sizes > 0)."""
    name, allowed, _, cli_args, arg = row
    env = _Env(setup, tmp_path)
    bad = []
    for x in VALUES:
        if name == "render checker" and x == 0.0:
            continue
        verdict, err = _python(row, x, env)
        r = run_cli(*cli_args(repr(x), env))
        cli = "ok" if r.returncode == 0 else "refused"
        if cli != verdict:
            bad.append(f"{x!r}: Python {verdict} ({err}), CLI exit {r.returncode} ({r.stderr.strip()[:200]})")
    assert not bad, f"{name}:\n  " + "\n  ".join(bad)


def test_subnormal_values_reach_the_library_whole(setup):
    """A subnormal max_distance is that distance: only the source itself is within it."""
    m = setup[0]
    for md in (5e-324, 1e-320):
        d = m.field(0, max_distance=md)
        assert d[0] == 0.0 and np.isinf(d[1:]).all(), (md, d[:4])
