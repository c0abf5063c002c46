"""Every error path: a trigeo.Error subclass with file, line and reason; never a crash."""
import gzip
import math
import pickle

import numpy as np
import pytest

import trigeo
from conftest import SPOT, grid


def test_hierarchy():
    for cls in (trigeo.InvalidArgumentError, trigeo.OutOfMemoryError, trigeo.FileError, trigeo.ParseError,
                trigeo.InvalidMeshError, trigeo.UnsupportedError, trigeo.CapacityError, trigeo.CancelledError):
        assert issubclass(cls, trigeo.Error) and issubclass(cls, Exception)
    assert issubclass(trigeo.InvalidArgumentError, ValueError) and issubclass(trigeo.FileError, OSError)


def test_missing_file_and_directory(tmp_path):
    with pytest.raises(trigeo.FileError, match="nope.obj"):
        trigeo.load(tmp_path / "nope.obj")
    with pytest.raises(trigeo.Error, match="directory"):
        trigeo.load(tmp_path)


def test_parse_error_names_file_and_line(tmp_path):
    p = tmp_path / "bad.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 zz\nf 1 2 3\n")
    with pytest.raises(trigeo.ParseError) as e:
        trigeo.load(p)
    assert e.value.file == str(p) and e.value.line == 4 and f"{p}:4" in str(e.value)
    assert e.value.status == "parse"
    again = pickle.loads(pickle.dumps(e.value))  # crosses process boundaries (Dask) intact
    assert type(again) is trigeo.ParseError and str(again) == str(e.value) and again.line == 4


def test_invalid_mesh_file(tmp_path):
    p = tmp_path / "idx.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    with pytest.raises(trigeo.InvalidMeshError) as e:
        trigeo.load(p)
    assert e.value.line == 4 and "out of range" in e.value.reason


def test_truncated_gz_and_binary_garbage(tmp_path):
    g = tmp_path / "t.obj.gz"
    g.write_bytes(gzip.compress(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")[:-9])
    with pytest.raises(trigeo.Error):
        trigeo.load(g)
    b = tmp_path / "x.ply"
    b.write_bytes(b"ply\nformat binary_little_endian 1.0\nelement vertex 99999999\n" + bytes(range(256)) * 3)
    with pytest.raises(trigeo.Error):
        trigeo.load(b)
    with pytest.raises(trigeo.InvalidArgumentError):
        trigeo.load(SPOT, format="3ds")


def test_unsupported_huge_coordinates():
    v = np.array([[0, 0, 0], [1e300, 0, 0], [0, 1e300, 0]], dtype=float)
    m = trigeo.Mesh(v, [[0, 1, 2]])
    with pytest.raises(trigeo.UnsupportedError):
        m.closest([[1.0, 1.0, 1.0]])


@pytest.mark.parametrize("vertices,faces,cls", [
    (np.zeros((3, 2)), [[0, 1, 2]], trigeo.InvalidArgumentError),
    (np.zeros((3, 3)), [[0, 1]], trigeo.InvalidArgumentError),
    (np.zeros((3, 3)), [[0, 1, 3]], trigeo.InvalidArgumentError),
    (np.zeros((3, 3)), [[0, -1, 2]], trigeo.InvalidArgumentError),
    (np.zeros((3, 3)), [[0.0, 1.0, 2.0]], trigeo.InvalidArgumentError),
    (np.array([[0, 0, 0], [1, np.nan, 0], [0, 1, 0]]), [[0, 1, 2]], trigeo.InvalidMeshError),
    (np.array([[0, 0, 0], [1, np.inf, 0], [0, 1, 0]]), [[0, 1, 2]], trigeo.InvalidMeshError),
    ([["a", "b", "c"]] * 3, [[0, 1, 2]], trigeo.InvalidArgumentError),
])
def test_bad_arrays(vertices, faces, cls):
    with pytest.raises(cls):
        trigeo.Mesh(vertices, faces)


@pytest.mark.parametrize("points", [np.zeros((4, 2)), [[0, 0, np.nan]], [[np.inf, 0, 0]], "abc", np.zeros((2, 3, 3))])
def test_bad_query_points(spot, points):
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.closest(points)
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.winding_number(points)


def test_bad_query_point_names_row(spot):
    q = np.zeros((5, 3))
    q[3, 1] = np.nan
    with pytest.raises(trigeo.InvalidArgumentError, match=r"points\[3\]"):
        spot.signed_distance(q)


@pytest.mark.parametrize("threads", [-1, 1.5, "2", True])
def test_bad_threads(spot, threads):
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.closest([[0.0, 0.0, 0.0]], threads=threads)


@pytest.mark.parametrize("endpoint", [-1, 2930, 10**12, trigeo.SurfacePoint(99999, (0.2, 0.3, 0.5)),
                                      trigeo.SurfacePoint(0, (0.5, 0.6, 0.5)), trigeo.SurfacePoint(0, (np.nan, 0.5, 0.5)),
                                      trigeo.SurfacePoint.edge(3 * 5856, 0.5), trigeo.SurfacePoint.edge(0, 1.5),
                                      (0.0, np.nan, 0.0), (1.0, 2.0), "v:0", None, True])
def test_bad_endpoints(spot, endpoint):
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.path(endpoint, 0)
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.field(endpoint if endpoint is not None else [[None]])


def test_bad_path_options(spot):
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.path(0, 1, method="dijkstra")
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.path_lengths(np.array([[0, 1, 2]]))
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.path_lengths(np.array([[0.0, 1.0]]))
    with pytest.raises(trigeo.InvalidArgumentError, match=r"pairs\[:, 1\]\[1\]"):
        spot.path_lengths(np.array([[0, 1], [2, 5000]]))
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.path_lengths(froms=[0, 1], tos=[2])
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.path_lengths(froms=[0, 1])
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.path_lengths(np.array([[0, 1]]), froms=[0], tos=[1])
    # a tuple of two pairs is two pairs, never (froms, tos)
    assert np.array_equal(spot.path_lengths(((0, 1), (2, 3))), spot.path_lengths(np.array([[0, 1], [2, 3]])))


def test_bad_field_options(spot):
    for md in (-1.0, math.nan, "far"):
        with pytest.raises((trigeo.InvalidArgumentError, TypeError, ValueError)):
            spot.field(0, max_distance=md)
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.distance_matrix([0], threads=-2)


def test_cancel_and_progress(spot):
    seen = []

    def stop(fraction):
        seen.append(fraction)
        return False

    big = trigeo.Mesh(*grid(200))
    with pytest.raises(trigeo.CancelledError):
        big.field(0, progress=stop)
    assert seen and 0.0 <= seen[0] <= 1.0

    def boom(fraction):
        raise KeyError("from the callback")

    with pytest.raises(KeyError):  # an exception in the callback stops the field and comes back as is
        big.field(0, progress=boom)
    assert np.isfinite(big.field(0, progress=lambda f: None)).all()  # None means go on


def test_render_errors(spot, tmp_path):
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.render(tmp_path / "a.png", field=np.zeros(3))
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.render(tmp_path / "a.png", width=0)
    with pytest.raises(trigeo.InvalidArgumentError):
        spot.render(tmp_path / "a.png", view=(0, 0, 0))
    with pytest.raises(trigeo.FileError):
        spot.render(tmp_path / "no" / "dir" / "a.png")
