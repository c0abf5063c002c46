"""bench_python.py: what the Python package costs over the C library, and what Dask buys.

    PYTHONPATH=python python3 bench/bench_python.py LARGE_MESH MESH [QUERIES] [PAIRS] [SOURCES]

1. Closest points: QUERIES (default 1,000,000) points near LARGE_MESH's surface (surface
   samples moved by up to 1% of the diagonal), random order. "C batch" is the bare call of
   tg_bvh_closest_batch through ctypes into a preallocated hit array (the C library's own
   work); "Python" is Mesh.closest end to end: input checks, the same call, and the conversion
   to (distance, face, point) arrays. Median of 5 alternating runs, 1 and 2 threads.
2. Dask throughput on MESH: PAIRS (default 2000) random vertex pairs through path_lengths (the
   default method, exact) and SOURCES (default 32) fields through distance_matrix, serially (one
   thread, in this process) and on a LocalCluster of 1 and 2 single-threaded worker processes
   (the first call, which loads the mesh on the workers, is timed separately as "warm-up");
   results are checked bit-identical to the serial ones.
"""
import ctypes
import math
import os
import statistics
import sys
import time

import numpy as np

import trigeo
import trigeo.dask
from trigeo import _lib


def near_queries(mesh, n, seed=1):
    rng = np.random.default_rng(seed)
    v, f = mesh.vertices, mesh.faces.astype(np.int64)
    faces = rng.integers(0, f.shape[0], n)
    b = rng.dirichlet((1, 1, 1), n)
    p = np.einsum("ij,ijk->ik", b, v[f[faces]])
    diag = np.linalg.norm(np.array(mesh.report["bbox_max"]) - np.array(mesh.report["bbox_min"]))
    d = rng.normal(size=(n, 3))
    d *= (rng.uniform(0, 0.01 * diag, n) / np.linalg.norm(d, axis=1))[:, None]
    return np.ascontiguousarray(p + d)


def closest_overhead(path, n):
    mesh = trigeo.load(path)
    q = near_queries(mesh, n)
    mesh.closest(q[:1000])  # builds the BVH
    bvh = mesh._get_bvh()
    hits = np.empty(n, dtype=np.dtype(_lib.ClosestHit))
    hp = hits.ctypes.data_as(ctypes.POINTER(_lib.ClosestHit))
    qp = q.ctypes.data_as(ctypes.POINTER(ctypes.c_double))
    print(f"### Closest points: {os.path.basename(path)} ({mesh.face_count} faces), {n} near queries, random order\n")
    print("| threads | C batch (ctypes, s) | Python Mesh.closest (s) | overhead | ns/query C | ns/query Python |")
    print("|---|---|---|---|---|---|")
    for threads in (1, 2):
        c_times, py_times = [], []
        for _ in range(5):
            t0 = time.perf_counter()
            st = _lib.lib.tg_bvh_closest_batch(bvh, qp, n, math.inf, threads, hp)
            c_times.append(time.perf_counter() - t0)
            assert st == 0
            t0 = time.perf_counter()
            d, face, p = mesh.closest(q, threads=threads)
            py_times.append(time.perf_counter() - t0)
        assert np.array_equal(d, np.sqrt(hits["sqdist"])) and np.array_equal(face, hits["face"].astype(np.int64))
        c, py = statistics.median(c_times), statistics.median(py_times)
        print(f"| {threads} | {c:.3f} | {py:.3f} | {100 * (py - c) / c:+.1f}% | {1e9 * c / n:.0f} | {1e9 * py / n:.0f} |")
    print()


def dask_throughput(path, npairs, nsources):
    from dask.distributed import Client, LocalCluster
    mesh = trigeo.load(path)
    rng = np.random.default_rng(2)
    pairs = rng.integers(0, mesh.vertex_count, size=(npairs, 2))
    sources = [int(s) for s in rng.integers(0, mesh.vertex_count, nsources)]
    t0 = time.perf_counter()
    want_l = mesh.path_lengths(pairs, threads=1)
    t_l = time.perf_counter() - t0
    t0 = time.perf_counter()
    want_m = mesh.distance_matrix(sources, threads=1)
    t_m = time.perf_counter() - t0
    print(f"### Dask: {os.path.basename(path)} ({mesh.face_count} faces), {npairs} path_lengths pairs (exact, the default) "
          f"(chunks of 100), {nsources} distance_matrix rows (chunks of 1)\n")
    print("| run | path_lengths s | pairs/s | distance_matrix s | rows/s | warm-up s (mesh load on workers) |")
    print("|---|---|---|---|---|---|")
    print(f"| serial, 1 thread, no Dask | {t_l:.2f} | {npairs / t_l:.0f} | {t_m:.2f} | {nsources / t_m:.2f} | - |")
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, dashboard_address=None) as cluster, \
                Client(cluster) as client:
            t0 = time.perf_counter()
            trigeo.dask.path_lengths(client, path, pairs[:workers], chunk=1)
            warm = time.perf_counter() - t0
            t0 = time.perf_counter()
            got_l = trigeo.dask.path_lengths(client, path, pairs, chunk=100)
            dl = time.perf_counter() - t0
            t0 = time.perf_counter()
            got_m = trigeo.dask.distance_matrix(client, path, sources, chunk=1)
            dm = time.perf_counter() - t0
        assert np.array_equal(got_l, want_l) and np.array_equal(got_m, want_m)
        print(f"| Dask LocalCluster, {workers} worker{'s' if workers > 1 else ''} | {dl:.2f} | {npairs / dl:.0f} | "
              f"{dm:.2f} | {nsources / dm:.2f} | {warm:.2f} |")
    print()


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    n = int(sys.argv[3]) if len(sys.argv) > 3 else 1_000_000
    npairs = int(sys.argv[4]) if len(sys.argv) > 4 else 2000
    nsources = int(sys.argv[5]) if len(sys.argv) > 5 else 32
    print(f"trigeo {trigeo.version()} ({_lib.lib_path}), Python {sys.version.split()[0]}, NumPy {np.__version__}\n")
    closest_overhead(sys.argv[1], n)
    dask_throughput(sys.argv[2], npairs, nsources)
