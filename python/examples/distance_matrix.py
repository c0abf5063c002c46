"""Geodesic distance matrix between sample points, serially and on a Dask cluster.

    PYTHONPATH=python python3 python/examples/distance_matrix.py [MESH] [K]

Picks K sample vertices by farthest-point sampling (Mesh.farthest_point_sampling from vertex 0:
each new sample is the vertex farthest, in geodesic distance, from those chosen so far), then
computes the K x K matrix of exact geodesic distances between them: once with Mesh.distance_matrix on this machine's cores, once on a
2-worker Dask LocalCluster (the same call runs on an SSH or HPC cluster: change the cluster).
The cluster is started under `if __name__ == "__main__":` - without the guard Dask's worker
processes would re-run this script and hang.
"""
import os
import sys
import time

import numpy as np

import trigeo
import trigeo.dask


def main() -> None:
    here = os.path.dirname(os.path.abspath(__file__))
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "..", "data", "nvd_spot.obj")
    k = int(sys.argv[2]) if len(sys.argv) > 2 else 16
    mesh = trigeo.load(path)
    samples = [int(v) for v in mesh.farthest_point_sampling(k, start=0)[0]]  # exact FPS from vertex 0

    t0 = time.perf_counter()
    rows = mesh.distance_matrix(samples)             # (k, n): every vertex, one row per sample
    serial = rows[:, samples]                         # (k, k) between the samples
    t1 = time.perf_counter()
    print(f"{mesh}: {k} x {k} geodesic distance matrix in {t1 - t0:.2f} s on this machine")
    print(f"  symmetric to {np.max(np.abs(serial - serial.T)):.2g} (exact distances are symmetric up to rounding)")

    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, Client(cluster) as client:
        t0 = time.perf_counter()
        dist = trigeo.dask.distance_matrix(client, path, samples)[:, samples]
        t1 = time.perf_counter()
    print(f"  on a 2-worker Dask LocalCluster in {t1 - t0:.2f} s (cluster start not counted); "
          f"identical to the serial matrix: {np.array_equal(dist, serial)}")


if __name__ == "__main__":
    main()
