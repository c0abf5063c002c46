"""The package as a user meets it: finding the library, help(), the README's one-liner, the
examples."""
import os
import pydoc
import subprocess
import sys

import numpy as np

import trigeo
from conftest import REPO, SPOT


def run_py(code_or_args, env_extra=None, drop=(), cwd=REPO, timeout=300):
    env = {k: v for k, v in os.environ.items() if k not in drop}
    env["PYTHONPATH"] = os.path.join(REPO, "python")
    env.update(env_extra or {})
    args = ["-c", code_or_args] if isinstance(code_or_args, str) else code_or_args
    return subprocess.run([sys.executable, *args], capture_output=True, text=True, env=env, cwd=cwd, timeout=timeout)


def test_done_means_one_liner():
    """The issue's own check, with the library found in the repository's build/."""
    if not os.path.exists(os.path.join(REPO, "build", "libtrigeo.so")):
        import pytest
        pytest.skip("no build/libtrigeo.so (another build directory)")
    r = run_py("import trigeo; print(trigeo.load('data/nvd_spot.obj').field([0]).max())", drop=("TRIGEO_LIB",))
    assert r.returncode == 0, r.stderr
    assert abs(float(r.stdout) - trigeo.load(SPOT).field([0]).max()) == 0


def test_missing_library_is_a_clear_import_error():
    r = run_py("import trigeo", env_extra={"TRIGEO_LIB": "/nonexistent/libtrigeo.so"})
    assert r.returncode != 0 and "ImportError" in r.stderr
    assert "TRIGEO_LIB: /nonexistent/libtrigeo.so (no such file)" in r.stderr


def test_help_is_readable():
    text = pydoc.render_doc(trigeo, renderer=pydoc.plaintext)
    for word in ("load", "Mesh", "closest", "signed_distance", "path_lengths", "distance_matrix", "SurfacePoint",
                 "ParseError", "TRIGEO_LIB"):
        assert word in text
    import trigeo.dask as tgd
    assert "__main__" in tgd.__doc__
    for name in trigeo.__all__:
        obj = getattr(trigeo, name)
        assert obj.__doc__, name
    for name in ("load", "closest", "signed_distance", "winding_number", "path", "path_lengths", "field",
                 "field_at", "distance_matrix", "render"):
        f = getattr(trigeo.Mesh, name, None) or getattr(trigeo, name)
        assert f.__doc__ and f.__annotations__, name


def test_pickle_round_trip():
    import pickle
    m = trigeo.Mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]]), np.array([[0, 1, 2]]))
    m2 = pickle.loads(pickle.dumps(m))
    assert np.array_equal(m2.vertices, m.vertices) and np.array_equal(m2.faces, m.faces)
    sp = trigeo.SurfacePoint.edge(2, 0.25)
    assert pickle.loads(pickle.dumps(sp)) == sp


def test_examples(tmp_path):
    ex = os.path.join(REPO, "python", "examples")
    png = tmp_path / "p.png"
    r = run_py([os.path.join(ex, "path_picture.py"), SPOT, str(png)])
    assert r.returncode == 0, r.stderr
    assert "(proven)" in r.stdout and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    r = run_py([os.path.join(ex, "distance_matrix.py"), SPOT, "6"])
    assert r.returncode == 0, r.stderr
    assert "identical to the serial matrix: True" in r.stdout
