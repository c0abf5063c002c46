"""trigeo.dask on a 2-worker LocalCluster (processes): equal to the serial calls bit for bit,
meshes cached on the workers, a failing chunk raises the worker's error naming the chunk."""
import os

import numpy as np
import pytest

import trigeo
import trigeo.dask as tgd
from conftest import SPOT, corpus

distributed = pytest.importorskip("distributed")
pytestmark = pytest.mark.cluster


@pytest.fixture(scope="module")
def client():
    env = {"PYTHONPATH": os.pathsep.join([os.path.join(os.path.dirname(__file__), "..")] +
                                        os.environ.get("PYTHONPATH", "").split(os.pathsep))}
    if "TRIGEO_LIB" in os.environ:
        env["TRIGEO_LIB"] = os.environ["TRIGEO_LIB"]
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                       env=env)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def test_closest_equals_serial(client):
    m = trigeo.load(SPOT)
    rng = np.random.default_rng(11)
    q = rng.uniform(-1, 1, size=(5000, 3))
    got = tgd.closest(client, SPOT, q, chunk=700)
    want = m.closest(q)
    for g, w in zip(got, want):
        assert g.dtype == w.dtype and np.array_equal(g, w)


def test_path_lengths_equal_serial(client):
    path = corpus("igl_decimated-knight.off")
    m = trigeo.load(path)
    rng = np.random.default_rng(12)
    pairs = rng.integers(0, m.vertex_count, size=(60, 2))
    for method in ("straighten", "exact"):
        got = tgd.path_lengths(client, m, pairs, method=method, chunk=7)
        assert np.array_equal(got, m.path_lengths(pairs, method=method))
    froms = [trigeo.SurfacePoint(3, (0.2, 0.3, 0.5)), 10]
    tos = [trigeo.SurfacePoint.edge(30, 0.25), trigeo.SurfacePoint(700, (0.1, 0.1, 0.8))]
    assert np.array_equal(tgd.path_lengths(client, path, froms=froms, tos=tos, chunk=1),
                          m.path_lengths(froms=froms, tos=tos))


def test_distance_matrix_from_arrays_scattered_once(client):
    m = trigeo.load(SPOT)
    arrays_mesh = trigeo.Mesh(m.vertices, m.faces)
    sources = [0, 100, 2000, trigeo.SurfacePoint(5, (0.3, 0.3, 0.4))]
    got = tgd.distance_matrix(client, arrays_mesh, sources, chunk=1)
    assert np.array_equal(got, m.distance_matrix(sources))
    first = arrays_mesh._dask_arrays
    got2 = tgd.distance_matrix(client, arrays_mesh, sources[:2], chunk=1)
    assert arrays_mesh._dask_arrays is first and np.array_equal(got2, got[:2])
    # each worker built each mesh once and kept it: the spot file, the knight file, the arrays
    counts = client.run(tgd.cached_meshes)
    assert all(1 <= n <= 3 for n in counts.values())


def test_failing_chunk_raises_the_workers_error(client, tmp_path):
    m = trigeo.load(SPOT)
    pairs = np.array([[0, 1]] * 10 + [[0, 2929]] * 10)
    pts = [trigeo.SurfacePoint(5, (0.3, 0.3, 0.4))] * 5 + [trigeo.SurfacePoint(5, (0.9, 0.9, 0.4))]
    with pytest.raises(trigeo.InvalidArgumentError, match=r"chunk 1 \(items 4-5\)"):
        tgd.path_lengths(client, SPOT, froms=pts, tos=pts, chunk=4)
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    with pytest.raises(trigeo.InvalidMeshError, match=r"chunk 0 .*bad.obj:4"):
        tgd.closest(client, str(bad), np.zeros((3, 3)))
    assert np.isfinite(tgd.path_lengths(client, SPOT, pairs, chunk=6)).all()


def _spot_variant(path, scale):
    """Spot with every coordinate times `scale` (same topology, other distances), written as OBJ."""
    m = trigeo.load(SPOT)
    trigeo.Mesh(m.vertices * scale, m.faces).save(path)


def test_the_mesh_given_not_the_files_newer_content(client, tmp_path):
    """The workers compute on the mesh given, not on its file read again: after m = trigeo.load(f)
    and a rewrite of f, distance_matrix(client, m) once used the new file."""
    f = str(tmp_path / "spot.obj")
    _spot_variant(f, 1.0)
    m = trigeo.load(f)
    want = m.distance_matrix([0, 7])
    assert np.array_equal(tgd.distance_matrix(client, m, [0, 7]), want)
    _spot_variant(f, 2.0)  # rewritten: twice the distances
    assert np.array_equal(tgd.distance_matrix(client, m, [0, 7]), want)  # the Mesh given
    assert np.array_equal(tgd.distance_matrix(client, f, [0, 7]), 2 * want)  # the path: the file now
    assert np.array_equal(tgd.distance_matrix(client, m, [0, 7]), want)


def test_an_edit_keeping_time_and_size_is_seen(client, tmp_path):
    """The worker cache was keyed by (path, mtime, size): an in-place edit keeping both returned
    stale rows (16 of 16) with no warning."""
    f = str(tmp_path / "spot.obj")
    _spot_variant(f, 1.0)
    before = trigeo.load(f)
    first = tgd.distance_matrix(client, f, list(range(16)))  # cached on the workers
    assert np.array_equal(first, before.distance_matrix(list(range(16))))
    st = os.stat(f)
    text = open(f).read()
    # the same bytes but one: vertex 0's first coordinate digit changes, the size stays
    i = text.index("\nv ") + 3
    digit = text[i + 1] if text[i] == "-" else text[i]
    j = i + 1 if text[i] == "-" else i
    text = text[:j] + ("1" if digit != "1" else "2") + text[j + 1:]
    open(f, "w").write(text)
    os.utime(f, ns=(st.st_atime_ns, st.st_mtime_ns))
    assert os.stat(f).st_size == st.st_size and os.stat(f).st_mtime_ns == st.st_mtime_ns
    after = trigeo.load(f)
    got = tgd.distance_matrix(client, f, list(range(16)))
    assert np.array_equal(got, after.distance_matrix(list(range(16))))
    assert not np.array_equal(got, first)
    assert np.array_equal(tgd.distance_matrix(client, before, list(range(16))), first)  # still the Mesh given


def test_a_missing_file_is_a_file_error(client, tmp_path):
    with pytest.raises(trigeo.FileError):
        tgd.distance_matrix(client, str(tmp_path / "nowhere.obj"), [0])


def test_sparse_and_selected_matrices_equal_serial(client):
    m = trigeo.load(SPOT)
    # an unused vertex at the end: the "all" matrix gives it an empty row, in any block
    v = np.vstack([m.vertices, [[5.0, 5.0, 5.0]]])
    arrays_mesh = trigeo.Mesh(v, m.faces)
    want = arrays_mesh.distance_matrix("all", max_distance=0.05, sparse=True)
    got = tgd.distance_matrix(client, arrays_mesh, "all", max_distance=0.05, sparse=True, chunk=700)
    assert got.shape == want.shape == (m.vertex_count + 1, m.vertex_count + 1)
    assert np.array_equal(got.indptr, want.indptr) and np.array_equal(got.indices, want.indices)
    assert np.array_equal(got.data, want.data) and got.indptr[-1] == got.indptr[-2]
    sources = [0, 100, trigeo.SurfacePoint(5, (0.3, 0.3, 0.4))]
    targets = [7, trigeo.SurfacePoint.edge(30, 0.25)]
    assert np.array_equal(tgd.distance_matrix(client, SPOT, sources, targets=targets, chunk=2),
                          m.distance_matrix(sources, targets=targets))


def test_all_without_sparse_is_refused_before_any_work():
    # "all" is the sparse matrix's word: without sparse=True it was split into the sources
    # 'a', 'l', 'l', each failing on a worker; now refused here, before the cluster is asked
    for sources in ("all", "some"):
        with pytest.raises(trigeo.InvalidArgumentError, match="sparse=True"):
            tgd.distance_matrix(None, SPOT, sources)
