"""trigeo batches on a Dask cluster (LocalCluster, SSH cluster, HPC schedulers via dask-jobqueue).

    from dask.distributed import Client, LocalCluster
    import trigeo, trigeo.dask

    if __name__ == "__main__":          # required: see below
        with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
            d, face, p = trigeo.dask.closest(client, "mesh.ply", points)
            lengths = trigeo.dask.path_lengths(client, "mesh.ply", pairs)
            matrix = trigeo.dask.distance_matrix(client, "mesh.ply", [0, 10, 20])
            local = trigeo.dask.distance_matrix(client, "mesh.ply", "all", max_distance=0.05, sparse=True)

The work is split into chunks, one task each. The mesh reaches each worker once and stays
there, with its BVH and geodesic solver, for every later task and call, and every task computes
on exactly the mesh the call was given, identified by content, never by a file's name, time or
size:
- given a path (str or os.PathLike), the client hashes the file's bytes when the call starts;
  each worker reads the file itself (a shared filesystem: the path must be readable on the
  client and the workers), and a worker that finds other bytes (the file changed during the
  call) raises trigeo.FileError;
- given a Mesh loaded from a file, each worker loads that file and compares the mesh it gets
  with the Mesh's vertices and faces (a hash of both); if the file has changed since
  trigeo.load, the Mesh's own arrays are scattered to the workers instead;
- given a Mesh made from arrays, its vertices and faces are scattered to the workers once.
Results come back in input order and are bit-identical to the serial Mesh calls. A chunk that
fails raises the worker's trigeo.Error (same class) in the client, its message naming the
chunk.

Worker processes start by re-importing the main module: a script that starts a LocalCluster
with processes must do so under `if __name__ == "__main__":`, and such a script cannot be
piped to `python3 -` (both hang: the workers re-run the cluster start). Each task runs its
chunk on `threads` C threads (default 1: Dask runs one task per worker thread).
"""
from __future__ import annotations

import hashlib
import os
import threading
import uuid
import warnings
from collections import OrderedDict
from typing import Any, Optional, Union

import numpy as np

import trigeo

__all__ = ["closest", "path_lengths", "distance_matrix", "cached_meshes"]

# Worker side: meshes by key, kept across tasks (a few at most; least recently used dropped). A
# mesh read from a file is kept under two keys: the file's path and bytes hash, and its content.
_CACHE: "OrderedDict[tuple, trigeo.Mesh]" = OrderedDict()
_CACHE_LOCK = threading.Lock()
_CACHE_SIZE = 8


def cached_meshes() -> int:
    """How many meshes this process keeps for Dask tasks (for tests and monitoring)."""
    with _CACHE_LOCK:
        return len({id(m) for m in _CACHE.values()})


def _content_hash(mesh: trigeo.Mesh) -> str:
    """A hash of the mesh's vertices and faces (their bytes and shapes), made once per Mesh."""
    h = getattr(mesh, "_content_hash", None)
    if h is None:
        v, f = mesh.vertices, mesh.faces
        d = hashlib.blake2b(digest_size=20, person=b"trigeo-mesh")
        d.update(np.array([v.shape[0], f.shape[0]], dtype="<u8").tobytes())
        d.update(np.ascontiguousarray(v, dtype="<f8").data)
        d.update(np.ascontiguousarray(f, dtype="<u4").data)
        h = mesh._content_hash = d.hexdigest()
    return h


def _read_file(path: str) -> bytes:
    try:
        with open(path, "rb") as fh:
            return fh.read()
    except OSError as e:
        raise trigeo.FileError(f"{path}: cannot read: {e.strerror}", path, 0, 0, f"cannot read: {e.strerror}") from None


def _bytes_hash(data: bytes) -> str:
    return hashlib.blake2b(data, digest_size=20, person=b"trigeo-file").hexdigest()


class _Changed(trigeo.FileError):
    """A worker found the file of a Mesh changed since it was loaded (the client then sends the
    Mesh's own arrays)."""


def _cached(key: tuple) -> Optional[trigeo.Mesh]:
    with _CACHE_LOCK:
        m = _CACHE.get(key)
        if m is not None:
            _CACHE.move_to_end(key)
        return m


def _remember(keys: tuple, m: trigeo.Mesh) -> trigeo.Mesh:
    with _CACHE_LOCK:
        for key in keys:
            _CACHE[key] = _CACHE.get(key, m)
            _CACHE.move_to_end(key)
        while len(_CACHE) > _CACHE_SIZE:
            _CACHE.popitem(last=False)
        return _CACHE[keys[0]]


def _worker_mesh(source: tuple, arrays: Any = None) -> trigeo.Mesh:
    """The mesh of a task, loaded or built once per worker process. source: ("mesh", content
    hash) with the scattered arrays, or ("file", path, hash of its bytes or None, content hash
    the mesh must have or None)."""
    if source[0] == "mesh":
        m = _cached(source)
        if m is None:
            m = trigeo.Mesh(arrays[0], arrays[1])
            if _content_hash(m) != source[1]:  # cannot happen: the arrays are the Mesh's own
                raise trigeo.InvalidArgumentError("trigeo.dask: the scattered arrays do not match their mesh")
            m = _remember((source,), m)
        return m
    _, path, file_hash, want = source
    m = _cached(("file", path, file_hash)) if file_hash else None
    if m is None:
        data = _read_file(path)
        got = _bytes_hash(data)
        if file_hash and got != file_hash:
            raise trigeo.FileError(f"{path}: the file changed during the call (its bytes differ from when the call "
                                   "started)", path, 0, 0, "the file changed during the call")
        m = _cached(("file", path, got))
        if m is None:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", trigeo.LoadWarning)  # the client's load warned already
                m = trigeo.load_bytes(data, path)
            m = _remember((("file", path, got), ("mesh", _content_hash(m))), m)
    if want and _content_hash(m) != want:
        raise _Changed(f"{path}: the file's mesh differs from the Mesh given (changed since trigeo.load)", path, 0, 0,
                       "changed since trigeo.load")
    return m


class _Source:
    """What a task needs to find its mesh: ("file", path, bytes hash, content hash) or ("mesh",
    content hash) with the scattered arrays' future."""

    def __init__(self, client: Any, mesh: Union[str, os.PathLike, trigeo.Mesh]):
        self.client, self.mesh, self.arrays = client, mesh, None
        if isinstance(mesh, trigeo.Mesh) and mesh.source is None:
            self.scatter()
        elif isinstance(mesh, trigeo.Mesh):
            self.key = ("file", mesh.source, None, _content_hash(mesh))
        else:
            path = os.path.abspath(trigeo._fs_path(mesh, "mesh path"))
            self.key = ("file", path, _bytes_hash(_read_file(path)), None)

    def scatter(self) -> None:
        """The Mesh's arrays on every worker, scattered once per client and mesh."""
        mesh, client = self.mesh, self.client
        cached = getattr(mesh, "_dask_arrays", None)
        if cached is None or cached[0] is not client or cached[1].status != "finished":
            # hash=False: a key of its own; the same arrays scattered again (the same mesh content
            # as a Mesh released a moment ago) could otherwise meet their old key being forgotten,
            # and Dask then waits forever
            [future] = client.scatter([(np.array(mesh.vertices), np.array(mesh.faces))], broadcast=True, hash=False)
            cached = (client, future)
            mesh._dask_arrays = cached
        self.key, self.arrays = ("mesh", _content_hash(mesh)), cached[1]


def _run(kind: str, source: tuple, arrays: Any, chunk: int, lo: int, hi: int, args: tuple) -> Any:
    try:
        m = _worker_mesh(source, arrays)
        if kind == "closest":
            return m.closest(args[0], threads=args[1])
        if kind == "path_lengths":
            froms, tos, method, certify, threads = args
            return m.path_lengths(froms=froms, tos=tos, method=method, certify=certify, threads=threads)
        if kind == "local_matrix":
            return _local_rows(m, *args)
        sources, max_distance, threads, targets = args
        return m.distance_matrix(sources, max_distance=max_distance, threads=threads, targets=targets)
    except _Changed:
        raise
    except trigeo.Error as e:
        raise type(e)(f"{kind}: chunk {chunk} (items {lo}-{hi - 1}): {e}", e.file, e.line, e.column,
                      e.reason) from None


def _local_rows(m: trigeo.Mesh, sources: Any, every: bool, max_distance: Optional[float], threads: int) -> Any:
    """A block of rows of the local matrix. every: sources are the block's vertex indices of
    distance_matrix(mesh, "all", ...), where a vertex no face uses gets an empty row."""
    if not every:
        return m.distance_matrix(sources, max_distance=max_distance, threads=threads, sparse=True)
    import scipy.sparse

    used = np.zeros(m.vertex_count, dtype=bool)
    used[m.faces.reshape(-1)] = True
    rows = np.asarray(sources, dtype=np.int64)
    keep = used[rows]
    part = m.distance_matrix(rows[keep], max_distance=max_distance, threads=threads, sparse=True)
    if keep.all():
        return part
    counts = np.zeros(len(rows), dtype=np.int64)
    counts[keep] = np.diff(part.indptr)
    indptr = np.concatenate(([0], np.cumsum(counts)))
    return scipy.sparse.csr_matrix((part.data, part.indices, indptr), shape=(len(rows), m.vertex_count))


def _map(client: Any, kind: str, mesh: Any, n: int, chunk: int, slicer, *extra) -> list:
    if not isinstance(chunk, int) or chunk < 1:
        raise trigeo.InvalidArgumentError(f"chunk must be a positive integer, not {chunk!r}")
    src = _Source(client, mesh)
    for attempt in range(2):
        futures = []
        for c, lo in enumerate(range(0, n, chunk)):
            hi = min(n, lo + chunk)
            futures.append(client.submit(_run, kind, src.key, src.arrays, c, lo, hi, slicer(lo, hi) + extra,
                                         pure=False, key=f"trigeo-{kind}-{uuid.uuid4().hex}-{c}"))
        try:
            return client.gather(futures)
        except _Changed:
            if attempt or src.arrays is not None:
                raise
            src.scatter()  # the Mesh's file has changed: its own arrays, to every worker
        finally:
            for f in futures:
                f.release()
    raise AssertionError("unreachable")


def closest(client: Any, mesh: Union[str, os.PathLike, trigeo.Mesh], points: Any, chunk: int = 262144,
            threads: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mesh.closest over a cluster: points (k, 3) in chunks of `chunk` rows. Returns (distance
    (k,), face (k,), point (k, 3)), identical to mesh.closest(points)."""
    p = trigeo._points(points)
    if p.shape[0] == 0:
        return np.empty(0), np.empty(0, np.int64), np.empty((0, 3))
    parts = _map(client, "closest", mesh, p.shape[0], chunk, lambda lo, hi: (p[lo:hi],), threads)
    return tuple(np.concatenate([r[i] for r in parts]) for i in range(3))


def path_lengths(client: Any, mesh: Union[str, os.PathLike, trigeo.Mesh], pairs: Any = None,
                 method: str = "exact", chunk: int = 256, certify: bool = False,
                 threads: int = 1, *, froms: Any = None, tos: Any = None) -> np.ndarray:
    """Mesh.path_lengths over a cluster: pairs a (k, 2) integer array of vertices, or froms= and
    tos= as Mesh.path_lengths takes them, in chunks of `chunk` pairs; method and certify as
    Mesh.path (default "exact": globally shortest, proven; "straighten" is the fast locally
    shortest one). Returns (k,) lengths."""
    if (pairs is None) == (froms is None and tos is None) or (pairs is None and (froms is None or tos is None)):
        raise trigeo.InvalidArgumentError("give either pairs (a (k, 2) array of vertices) or both froms= and tos=")
    if pairs is None:
        froms = froms if isinstance(froms, np.ndarray) else list(froms)
        tos = tos if isinstance(tos, np.ndarray) else list(tos)
    else:
        pa = np.asarray(pairs)
        if pa.ndim != 2 or pa.shape[1] != 2 or (pa.size and pa.dtype.kind not in "iu"):
            raise trigeo.InvalidArgumentError(
                f"pairs must be a (k, 2) integer array of vertices, not shape {pa.shape} dtype {pa.dtype}")
        froms, tos = pa[:, 0].astype(np.int64), pa[:, 1].astype(np.int64)
    if len(froms) != len(tos):
        raise trigeo.InvalidArgumentError(f"froms and tos differ in length ({len(froms)} and {len(tos)})")
    if len(froms) == 0:
        return np.empty(0)
    parts = _map(client, "path_lengths", mesh, len(froms), chunk, lambda lo, hi: (froms[lo:hi], tos[lo:hi]),
                 method, certify, threads)
    return np.concatenate(parts)


def distance_matrix(client: Any, mesh: Union[str, os.PathLike, trigeo.Mesh], sources: Any,
                    chunk: Optional[int] = None, max_distance: Optional[float] = None, threads: int = 1, *,
                    targets: Any = None, sparse: bool = False) -> Any:
    """Mesh.distance_matrix over a cluster: sources (vertex indices, SurfacePoints or
    positions) in blocks of `chunk` rows (default 1 for dense rows, 4096 for sparse ones).
    Returns the (K, n) matrix, row i bit-identical to mesh.field(sources[i]); with targets=,
    the (K, T) matrix to those points (each field stopped once they are settled); with
    sparse=True, the local matrix within max_distance as one scipy.sparse.csr_matrix, its row
    blocks computed on the workers and stacked in order (sources may be "all": every vertex)."""
    if chunk is None:
        chunk = 4096 if sparse else 1
    every = sparse and (sources is None or (isinstance(sources, str) and sources == "all"))
    if every:
        if not isinstance(mesh, trigeo.Mesh):
            mesh = trigeo.load(mesh)
        src: Any = np.arange(mesh.vertex_count)
    else:
        if isinstance(sources, str):
            raise trigeo.InvalidArgumentError(
                f'sources={sources!r}: "all" goes with sparse=True (and max_distance=D); otherwise give surface points')
        if isinstance(sources, (int, np.integer, trigeo.SurfacePoint)):
            sources = [sources]
        src = list(sources) if not isinstance(sources, np.ndarray) else sources
    if len(src) == 0:
        raise trigeo.InvalidArgumentError("distance_matrix needs at least one source")
    if targets is not None and sparse:
        raise trigeo.InvalidArgumentError("targets gives a dense (K, T) matrix: sparse=True does not apply")
    if sparse:
        import scipy.sparse

        parts = _map(client, "local_matrix", mesh, len(src), chunk, lambda lo, hi: (src[lo:hi],), every,
                     max_distance, threads)
        return scipy.sparse.vstack(parts, format="csr")
    if targets is not None and not isinstance(targets, np.ndarray):
        targets = [targets] if isinstance(targets, (int, np.integer, trigeo.SurfacePoint)) else list(targets)
    parts = _map(client, "distance_matrix", mesh, len(src), chunk, lambda lo, hi: (src[lo:hi],), max_distance,
                 threads, targets)
    return np.concatenate(parts, axis=0)
