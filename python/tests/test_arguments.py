"""Bad arguments to every public call raise trigeo.InvalidArgumentError naming the argument and
what it accepts: never a bare TypeError, IndexError, KeyError or NumPy's ValueError from deep
inside. And the seed of farthest_point_sampling takes the CLI's range (0 .. 2**64 - 1) and gives
the CLI's samples."""
import math
import os
import re

import numpy as np
import pytest

import trigeo
from conftest import grid, run_cli


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    """A 6 x 6 bumpy grid (36 vertices), loaded from a file."""
    v, f = grid(6)
    path = tmp_path_factory.mktemp("mesh") / "grid.obj"
    trigeo.Mesh(v, f).save(path)
    return trigeo.load(path)


def _curves(m):
    return m.isolines(0, [1.0, 2.0])


N = 36
RAGGED = [[0.0, 0.0, 0.0], [1.0, 1.0]]

# (argument named in the message, call on the small mesh m with a scratch folder d)
BAD = [
    # render: the two, then every argument
    ("isolines", lambda m, d: m.render(d / "a.png", isolines=3.5)),
    ("isoline_levels", lambda m, d: m.render(d / "a.png", isolines=_curves(m), isoline_levels=[1.0])),
    ("isoline_levels", lambda m, d: m.render(d / "a.png", isolines=_curves(m), isoline_levels=[])),
    ("isoline_levels", lambda m, d: m.render(d / "a.png", isolines=_curves(m), isoline_levels=[1.0, math.nan])),
    ("isoline_levels", lambda m, d: m.render(d / "a.png", isolines=_curves(m), isoline_levels=[1.0, -2.0])),
    ("isoline_levels", lambda m, d: m.render(d / "a.png", isolines=_curves(m), isoline_levels="ab")),
    ("isoline_levels", lambda m, d: m.render(d / "a.png", isolines=4, isoline_levels=[1.0])),
    ("isolines", lambda m, d: m.render(d / "a.png", isolines=-1)),
    ("isolines", lambda m, d: m.render(d / "a.png", isolines=True)),
    ("isolines", lambda m, d: m.render(d / "a.png", isolines="16")),
    ("isolines", lambda m, d: m.render(d / "a.png", isolines=np.float64(3.0))),
    ("isolines", lambda m, d: m.render(d / "a.png", isolines=2**40)),
    (r"isolines\[0\]", lambda m, d: m.render(d / "a.png", isolines=[5])),
    (r"isolines\[0\]", lambda m, d: m.render(d / "a.png", isolines=[[{"pts": np.zeros((2, 3))}]])),
    (r"isolines\[0\]\[0\]", lambda m, d: m.render(d / "a.png", isolines=[[np.zeros((2, 2))]])),
    (r"isolines\[0\]\[0\]", lambda m, d: m.render(d / "a.png", isolines=[[[[0, 0, 0], [1, 1]]]])),
    ("width", lambda m, d: m.render(d / "a.png", width=1.5)),
    ("width", lambda m, d: m.render(d / "a.png", width=True)),
    ("width", lambda m, d: m.render(d / "a.png", width="960")),
    ("height", lambda m, d: m.render(d / "a.png", height=0)),
    ("height", lambda m, d: m.render(d / "a.png", height=None)),
    ("view", lambda m, d: m.render(d / "a.png", view=(0, 0, 0))),
    ("view", lambda m, d: m.render(d / "a.png", view=(math.nan, 0, 1))),
    ("view", lambda m, d: m.render(d / "a.png", view=(0, 1))),
    ("view", lambda m, d: m.render(d / "a.png", view="up")),
    ("view", lambda m, d: m.render(d / "a.png", view=[[0, 0, 1], [1, 0, 0]])),
    ("view", lambda m, d: m.render(d / "a.png", view=[[0, 0], [1]])),
    ("field", lambda m, d: m.render(d / "a.png", field=np.zeros(3))),
    ("field", lambda m, d: m.render(d / "a.png", field="abc")),
    ("field", lambda m, d: m.render(d / "a.png", field=[[1.0, 2.0], [3.0]])),
    ("field", lambda m, d: m.render(d / "a.png", field=[None] * N)),
    ("labels", lambda m, d: m.render(d / "a.png", labels=np.zeros(N))),
    ("labels", lambda m, d: m.render(d / "a.png", labels=np.full(N, -2))),
    ("labels", lambda m, d: m.render(d / "a.png", labels=np.full(N, 2**33))),
    ("labels", lambda m, d: m.render(d / "a.png", labels="x")),
    ("labels", lambda m, d: m.render(d / "a.png", labels=[[0], [1, 2]])),
    ("logmap", lambda m, d: m.render(d / "a.png", logmap=np.zeros((N, 3)))),
    ("logmap", lambda m, d: m.render(d / "a.png", logmap=np.full((N, 2), math.nan))),
    ("logmap", lambda m, d: m.render(d / "a.png", logmap="uv")),
    ("checker", lambda m, d: m.render(d / "a.png", logmap=np.zeros((N, 2)), checker=math.nan)),
    ("checker", lambda m, d: m.render(d / "a.png", logmap=np.zeros((N, 2)), checker=-1.0)),
    ("checker", lambda m, d: m.render(d / "a.png", logmap=np.zeros((N, 2)), checker=math.inf)),
    ("checker", lambda m, d: m.render(d / "a.png", logmap=np.zeros((N, 2)), checker="big")),
    ("path", lambda m, d: m.render(d / "a.png", path=5)),
    ("path", lambda m, d: m.render(d / "a.png", path="abc")),
    ("path", lambda m, d: m.render(d / "a.png", path=np.zeros((3, 2)))),
    ("path", lambda m, d: m.render(d / "a.png", path=[[0, 0, math.nan], [1, 1, 0]])),
    ("path", lambda m, d: m.render(d / "a.png", path=RAGGED)),
    ("boundaries", lambda m, d: m.render(d / "a.png", boundaries=5)),
    (r"boundaries\[0\]", lambda m, d: m.render(d / "a.png", boundaries=[{"cells": (0, 1)}])),
    (r"boundaries\[0\]", lambda m, d: m.render(d / "a.png", boundaries=[np.zeros((2, 2))])),
    ("boundaries", lambda m, d: m.render(d / "a.png", path=np.zeros((2, 3)), boundaries=[np.zeros((2, 3))])),
    # sampling
    ("count", lambda m, d: m.farthest_point_sampling(2.5)),
    ("count", lambda m, d: m.farthest_point_sampling(0)),
    ("count", lambda m, d: m.farthest_point_sampling(-1)),
    ("count", lambda m, d: m.farthest_point_sampling(N + 1)),
    ("seed", lambda m, d: m.farthest_point_sampling(2, seed=-1)),
    ("seed", lambda m, d: m.farthest_point_sampling(2, seed=2**64)),
    ("seed", lambda m, d: m.farthest_point_sampling(2, seed=1.0)),
    ("seed", lambda m, d: m.farthest_point_sampling(2, seed="7")),
    ("start", lambda m, d: m.farthest_point_sampling(2, start="v:0")),
    ("start", lambda m, d: m.farthest_point_sampling(2, start=N)),
    ("progress", lambda m, d: m.farthest_point_sampling(2, progress=5)),
    # fields
    ("max_distance", lambda m, d: m.field(0, max_distance="far")),
    ("max_distance", lambda m, d: m.field(0, max_distance=[1.0])),
    ("max_distance", lambda m, d: m.field(0, max_distance=math.nan)),
    ("max_distance", lambda m, d: m.field(0, max_distance=-1.0)),
    ("max_distance", lambda m, d: m.field(0, max_distance=math.inf)),
    ("max_distance", lambda m, d: m.field(0, max_distance=10**400)),
    ("sources", lambda m, d: m.field([[0.0, 0.0], [1.0]])),
    ("progress", lambda m, d: m.field(0, progress="yes")),
    ("max_distance", lambda m, d: m.field_at(0, [1], max_distance=-0.5)),
    ("points", lambda m, d: m.field_at(0, RAGGED)),
    ("max_distance", lambda m, d: m.log_map(0, max_distance=math.nan)),
    ("ref", lambda m, d: m.log_map(0, ref=(0, 0, 0))),
    ("ref", lambda m, d: m.log_map(0, ref="x")),
    ("ref", lambda m, d: m.log_map(0, ref=(1, 2))),
    ("ref", lambda m, d: m.log_map(0, ref=(math.nan, 0, 0))),
    ("ref", lambda m, d: m.log_map(0, ref=[[1, 0], [0]])),
    ("levels", lambda m, d: m.isolines(0, "a")),
    ("levels", lambda m, d: m.isolines(0, [])),
    ("levels", lambda m, d: m.isolines(0, [1.0, math.nan])),
    ("levels", lambda m, d: m.isolines(0, [-1.0])),
    ("levels", lambda m, d: m.isolines(0, [[1.0, 2.0], [3.0]])),
    ("levels", lambda m, d: m.isolines(0, None)),
    ("max_distance", lambda m, d: m.voronoi([0, 5], max_distance="1")),
    ("max_distance", lambda m, d: m.distance_matrix([0], max_distance=-1.0)),
    ("max_distance", lambda m, d: m.distance_matrix([0], max_distance=math.inf, sparse=True)),
    ("threads", lambda m, d: m.distance_matrix([0], threads="2")),
    # traces
    ("length", lambda m, d: m.trace(14, 0.0, math.nan)),
    ("length", lambda m, d: m.trace(14, 0.0, -1.0)),
    ("length", lambda m, d: m.trace(14, 0.0, "x")),
    ("length", lambda m, d: m.trace(14, 0.0, math.inf)),
    ("direction", lambda m, d: m.trace(14, (0, 0, 0), 1.0)),
    ("direction", lambda m, d: m.trace(14, "x", 1.0)),
    ("direction", lambda m, d: m.trace(14, (1, math.nan, 0), 1.0)),
    ("direction", lambda m, d: m.trace(14, (1, 2), 1.0)),
    ("max_steps", lambda m, d: m.trace(14, 0.0, 1.0, max_steps=-1)),
    ("max_steps", lambda m, d: m.trace(14, 0.0, 1.0, max_steps=1.5)),
    ("lengths", lambda m, d: m.trace_batch([7, 8, 9], (1, 0, 0), [1.0, 2.0])),
    ("length", lambda m, d: m.trace_batch([7, 8, 9], (1, 0, 0), [[1.0], [2.0, 3.0]])),
    ("directions", lambda m, d: m.trace_batch([7, 8, 9], np.ones((2, 3)), 1.0)),
    ("direction", lambda m, d: m.trace_batch([7, 8, 9], [[1, 0, 0], [1, 0]], 1.0)),
    # paths and points
    ("method", lambda m, d: m.path(0, 5, method=[])),
    ("method", lambda m, d: m.path(0, 5, method="dijkstra")),
    ("method", lambda m, d: m.path_lengths([[0, 1]], method=None)),
    ("pairs", lambda m, d: m.path_lengths([[0, 1], [2]])),
    ("method", lambda m, d: m.signed_distance([[0.0, 0.0, 0.0]], method=[])),
    ("points", lambda m, d: m.closest(RAGGED)),
    ("points", lambda m, d: m.winding_number(RAGGED)),
    ("xyz", lambda m, d: m.locate([[0.0, 0.0], [1.0]])),
    ("direction", lambda m, d: m.trace(14, [[1, 2], [3]], 1.0)),
    # yes/no arguments: an array has no truth value
    ("certify", lambda m, d: m.path(0, 5, certify=np.zeros(2))),
    ("certify", lambda m, d: m.path_lengths([[0, 5]], certify="yes")),
    ("closed", lambda m, d: m.path_through([0, 5, 10], closed=np.zeros(2))),
    ("angles", lambda m, d: m.trace_batch([7, 8], 0.0, 1.0, angles=np.ones(2))),
    ("sparse", lambda m, d: m.distance_matrix([0], sparse=np.zeros(2))),
    ("boundaries", lambda m, d: m.voronoi([0, 35], boundaries=[True])),
    ("details", lambda m, d: m.isolines(0, [1.0], details=2)),
    # construction and files
    ("png_path", lambda m, d: m.render(None)),
    ("png_path", lambda m, d: m.render(3.5)),
    ("path", lambda m, d: m.save(["a.obj"])),
    ("path", lambda m, d: trigeo.load(None)),
    ("kind", lambda m, d: trigeo.SurfacePoint(0, kind=np.zeros((2, 2)))),
    ("vertices", lambda m, d: trigeo.Mesh(RAGGED, [[0, 1, 2]])),
    ("format", lambda m, d: trigeo.load(m.source, format=[])),
    ("format", lambda m, d: trigeo.load_bytes(b"v 0 0 0\n", format=["obj"])),
    ("data", lambda m, d: trigeo.load_bytes(5)),
    ("data", lambda m, d: trigeo.load_bytes("v 0 0 0\n")),
    ("barycentric", lambda m, d: trigeo.SurfacePoint(0, "abc")),
    ("barycentric", lambda m, d: trigeo.SurfacePoint(0, 5)),
    ("barycentric", lambda m, d: trigeo.SurfacePoint(0, (0.5, None, 0.5))),
    ("SurfacePoint t", lambda m, d: trigeo.SurfacePoint.edge(0, "half")),
    ("fields", lambda m, d: m.save(d / "a.ply", fields=[("d", np.zeros(N))])),
    ("field 'd'", lambda m, d: m.save(d / "a.ply", fields={"d": "abc"})),
    ("field 'd'", lambda m, d: m.save(d / "a.ply", fields={"d": [[1.0], [2.0, 3.0]]})),
    ("field 'd'", lambda m, d: m.save(d / "a.ply", fields={"d": np.zeros(3)})),
    # geodesic_mean and bezier (test_mean.py holds their oracles)
    ("points", lambda m, d: m.geodesic_mean([])),
    ("weights", lambda m, d: m.geodesic_mean([0, 1], weights=[1, -1])),
    ("weights", lambda m, d: m.geodesic_mean([0, 1], weights=[0, 0])),
    ("weights", lambda m, d: m.geodesic_mean([0, 1], weights=[1, 2, 3])),
    ("weights", lambda m, d: m.geodesic_mean([0, 1], weights="ab")),
    ("tolerance", lambda m, d: m.geodesic_mean([0, 1], tolerance=0)),
    ("max_iterations", lambda m, d: m.geodesic_mean([0, 1], max_iterations=0)),
    ("max_iterations", lambda m, d: m.geodesic_mean([0, 1], max_iterations=1.5)),
    ("uniqueness", lambda m, d: m.geodesic_mean([0, 1], uniqueness="yes")),
    ("start", lambda m, d: m.geodesic_mean([0, 1], start=N)),
    ("points", lambda m, d: m.bezier([])),
    ("samples", lambda m, d: m.bezier([0, 1], samples=1)),
    ("samples", lambda m, d: m.bezier([0, 1], samples=2.5)),
    ("method", lambda m, d: m.bezier([0, 1], method="straight")),
    ("count", lambda m, d: m.centroidal_voronoi(0)),
    ("count", lambda m, d: m.centroidal_voronoi(N + 1)),
    ("iterations", lambda m, d: m.centroidal_voronoi(3, iterations=0)),
    ("start", lambda m, d: m.centroidal_voronoi(3, start=[0, 1])),
    ("tolerance", lambda m, d: m.centroidal_voronoi(3, tolerance=-1.0)),
    ("seed", lambda m, d: m.centroidal_voronoi(3, seed=-1)),
]


@pytest.mark.parametrize("name,call", BAD, ids=[f"{i}-{re.sub(r'[^a-z_]', '', n)}" for i, (n, _) in enumerate(BAD)])
def test_bad_argument_is_a_clear_error(small, tmp_path, name, call):
    try:
        call(small, tmp_path)
    except trigeo.InvalidArgumentError as e:
        assert re.search(name, str(e)), f"the message does not name {name!r}: {e}"
    except Exception as e:  # a bare TypeError, IndexError, NumPy ValueError...
        pytest.fail(f"{type(e).__name__} instead of trigeo.InvalidArgumentError naming {name!r}: {e}")
    else:
        pytest.fail(f"accepted (expected an InvalidArgumentError naming {name!r})")
    assert os.listdir(tmp_path) == [], f"a refused call wrote {os.listdir(tmp_path)}"


def test_good_render_arguments_still_draw(small, tmp_path):
    """The checks refuse only what is wrong: the documented forms still draw."""
    m = small
    d = m.field(0)
    curves = _curves(m)
    labels, _, lines = m.voronoi([0, 35], boundaries=True)
    r, theta, uv = m.log_map(14)
    calls = {
        "bands": dict(field=d, isolines=0),
        "curves": dict(field=d, isolines=curves, isoline_levels=[1.0, 2.0]),
        "curves without levels": dict(field=d, isolines=curves),
        "curve dicts": dict(field=d, isolines=m.isolines(0, [1.5], details=True), isoline_levels=np.array([1.5])),
        "no curves": dict(isolines=[]),
        "labels and boundaries": dict(labels=labels, boundaries=lines),
        "boundary arrays": dict(boundaries=[ln["points"] for ln in lines]),
        "log map": dict(logmap=uv, checker=0.5),
        "path": dict(path=m.path(0, 35), view=(0, 0, -1)),
        "empty path": dict(path=[]),
        "view as a list": dict(view=[0.0, 1.0, -1.0], width=np.int32(40), height=30),
    }
    for what, kw in calls.items():
        out = tmp_path / f"{what.replace(' ', '_')}.PNG"
        kw.setdefault("width", 40)
        kw.setdefault("height", 30)
        m.render(out, **kw)
        assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", what


def _cli_samples(mesh_path, seed, tmp_path):
    out = tmp_path / f"s{seed}.txt"
    r = run_cli("sample", mesh_path, "--count", "4", "--seed", str(seed), "-o", str(out), "--quiet")
    assert r.returncode == 0, f"trigeo sample --seed {seed}: {r.returncode} {r.stderr}"
    return [int(line.split(":")[1]) for line in out.read_text().split()]


@pytest.mark.parametrize("seed", [2**32 - 1, 2**32, 2**32 + 5, 2**63 + 12345, 2**64 - 1])
def test_seed_takes_the_cli_range_and_gives_its_samples(small, tmp_path, seed):
    """The issue: seed=4294967295 was "out of range" in Python; the CLI takes any 64-bit seed."""
    py = small.farthest_point_sampling(4, seed=seed)[0].tolist()
    cli = _cli_samples(small.source, seed, tmp_path)
    assert py == cli, f"seed {seed}: Python {py}, CLI {cli}"


def test_seed_beyond_64_bits_refused_by_both(small, tmp_path):
    for seed in (2**64, -1):
        r = run_cli("sample", small.source, "--count", "2", "--seed", str(seed), "--quiet")
        assert r.returncode == 1, f"CLI --seed {seed}: {r.returncode} {r.stderr}"
        with pytest.raises(trigeo.InvalidArgumentError, match="seed"):
            small.farthest_point_sampling(2, seed=seed)


def test_seeds_pick_different_starts(small):
    """The seed reaches the library whole: seeds that differ only above bit 32 pick different
    first samples here (SplitMix64 mixes every bit)."""
    firsts = {int(small.farthest_point_sampling(1, seed=s)[0][0]) for s in (5, 5 + 2**32, 5 + 2**40, 5 + 2**63)}
    assert len(firsts) > 1, firsts
