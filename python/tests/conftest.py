"""Shared fixtures of the Python tests: where the repository, the CLI and the corpus are.
make test runs these through CTest (tests/CMakeLists.txt), which sets TG_TRIGEO (the CLI),
TG_MESHES_DIR (../shared/meshes) and TRIGEO_LIB (the library of the same build)."""
import os
import signal
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(REPO, "python"))

import trigeo  # noqa: E402

SPOT = os.path.join(REPO, "data", "nvd_spot.obj")


def pytest_configure(config):
    # CTest runs `-m "not cluster"` in the fast suite (python_tests) and `-m cluster` in the full
    # one (python_cluster, make check)
    config.addinivalue_line("markers", "cluster: needs a local Dask cluster (the full suite only)")


def cli_path() -> str:
    return os.environ.get("TG_TRIGEO", os.path.join(REPO, "build", "trigeo"))


def meshes_dir() -> str:
    return os.environ.get("TG_MESHES_DIR", os.path.normpath(os.path.join(REPO, "..", "shared", "meshes")))


def corpus(name: str) -> str:
    p = os.path.join(meshes_dir(), name)
    if not os.path.exists(p):
        pytest.skip(f"corpus mesh {p} not present")
    return p


def cpu_seconds(pid: int) -> float:
    """User + system CPU time of a running process (all its threads), from /proc."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()  # fields from the 3rd (state) on
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")  # utime, stime


def interrupt(p: subprocess.Popen, timeout: float = 60):
    """Sends SIGINT to p, a Python child that prints "interrupted CPU" (CPU: its
    time.process_time()) when the KeyboardInterrupt reaches it. Returns (the CPU seconds the
    child spent between the signal and the interrupt, or None if it did not print that line,
    its output). CPU time, not wall time: on a loaded machine the child may wait seconds for a
    core, but the work it does after the signal is what shows whether the call stopped."""
    cpu0 = cpu_seconds(p.pid)
    p.send_signal(signal.SIGINT)
    try:
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        p.kill()
        out, err = p.communicate()
        return None, (out or "") + (err or "") + f" (still running {timeout} s after Ctrl-C)"
    lines = (out or "").strip().splitlines()
    if not lines or not lines[-1].startswith("interrupted "):
        return None, (out or "") + (err or "")
    return float(lines[-1].split()[1]) - cpu0, (out or "") + (err or "")


def run_cli(*args: str, stdin: str = None) -> subprocess.CompletedProcess:
    return subprocess.run([cli_path(), *args], input=stdin, capture_output=True, text=True, check=False)


def grid(n: int, amplitude: float = 0.05):
    """An n x n height-field grid mesh (vertices, faces), gently bumpy."""
    import numpy as np
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    z = amplitude * np.sin(i.ravel() * 0.3) * np.cos(j.ravel() * 0.2)
    v = np.stack([i.ravel(), j.ravel(), z], axis=1).astype(float)
    a = (i[:-1, :-1] * n + j[:-1, :-1]).ravel()
    f = np.concatenate([np.stack([a, a + n, a + n + 1], 1), np.stack([a, a + n + 1, a + 1], 1)])
    return v, f


def flat_grid(n: int) -> "trigeo.Mesh":
    """The unit square z = 0 as an n x n grid of vertices (n + 1)^2, two triangles a cell: a flat
    mesh whose geodesic distances are the Euclidean ones (curve tests)."""
    import numpy as np
    import trigeo
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
    v = np.stack([i.ravel() / n, j.ravel() / n, np.zeros(i.size)], axis=1)
    a = (i[:-1, :-1] * (n + 1) + j[:-1, :-1]).ravel()
    f = np.concatenate([np.stack([a, a + n + 1, a + n + 2], 1), np.stack([a, a + n + 2, a + 1], 1)])
    return trigeo.Mesh(v, f)


def seg_dist(p, a, b):
    """Euclidean distance from each row of p (k, 3) to the segment a b."""
    import numpy as np
    t = np.clip(((p - a) @ (b - a)) / ((b - a) @ (b - a)), 0, 1)
    return np.linalg.norm(p - (a + t[:, None] * (b - a)), axis=1)


@pytest.fixture(scope="session")
def spot() -> "trigeo.Mesh":
    return trigeo.load(SPOT)
