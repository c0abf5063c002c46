"""Shared fixtures of the Python tests: where the repository, the CLI and the corpus are.
make test runs these through CTest (tests/CMakeLists.txt), which sets TG_TRIGEO (the CLI),
TG_MESHES_DIR (../shared/meshes) and TRIGEO_LIB (the library of the same build)."""
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(REPO, "python"))

import trigeo  # noqa: E402

SPOT = os.path.join(REPO, "data", "nvd_spot.obj")


def cli_path() -> str:
    return os.environ.get("TG_TRIGEO", os.path.join(REPO, "build", "trigeo"))


def meshes_dir() -> str:
    return os.environ.get("TG_MESHES_DIR", os.path.normpath(os.path.join(REPO, "..", "shared", "meshes")))


def corpus(name: str) -> str:
    p = os.path.join(meshes_dir(), name)
    if not os.path.exists(p):
        pytest.skip(f"corpus mesh {p} not present")
    return p


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


@pytest.fixture(scope="session")
def spot() -> "trigeo.Mesh":
    return trigeo.load(SPOT)
