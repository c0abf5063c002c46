"""Where `import trigeo` looks for libtrigeo.so: only TRIGEO_LIB, the checkout's own build/, the
library inside the package, or the one `make install` put beside it. A libtrigeo.so planted in a
folder above a checkout or an installed package is never loaded (loading it would run its
constructor), and the ImportError names where it looked."""
import os
import shutil
import subprocess
import sys

import pytest

import trigeo
from trigeo import _lib

PKG = os.path.dirname(os.path.realpath(trigeo.__file__))


@pytest.fixture
def planted(tmp_path):
    """A libtrigeo.so whose constructor creates a file: (the library, the file it creates)."""
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        pytest.skip("no C compiler to build the planted library")
    mark = tmp_path / "constructor_ran"
    src = tmp_path / "planted.c"
    src.write_text("#include <stdio.h>\n"
                   "__attribute__((constructor)) static void ran(void)\n"
                   "{ FILE* f = fopen(MARK, \"w\"); if (f) fclose(f); }\n")
    so = tmp_path / "planted.so"
    subprocess.run([cc, "-shared", "-fPIC", f'-DMARK="{mark}"', "-o", str(so), str(src)], check=True)
    return so, mark


def _package(dest):
    """A copy of the package's Python files (no library, no install mark) at dest/trigeo."""
    shutil.copytree(PKG, os.path.join(dest, "trigeo"),
                    ignore=shutil.ignore_patterns("__pycache__", "*.so", "*.so.*", "_installed_beside_lib"))
    return os.path.join(dest, "trigeo")


def _plant(so, *paths):
    for p in paths:
        os.makedirs(os.path.dirname(p), exist_ok=True)
        shutil.copyfile(so, p)


def _import(python_path, cwd):
    env = {k: v for k, v in os.environ.items() if k not in ("TRIGEO_LIB", "PYTHONPATH")}
    env["PYTHONPATH"] = python_path
    return subprocess.run([sys.executable, "-c", "import trigeo; print(trigeo._lib.lib_path)"], capture_output=True,
                          text=True, env=env, cwd=cwd, timeout=120)


def test_checkout_without_build_loads_nothing_from_its_parent(planted, tmp_path):
    """The issue's case: a checkout directly inside a shared folder, not built; the old code
    loaded SHARED/libtrigeo.so (python/trigeo/../../../libtrigeo.so)."""
    so, mark = planted
    shared = tmp_path / "shared"
    checkout = shared / "checkout"
    (checkout / "include").mkdir(parents=True)
    (checkout / "CMakeLists.txt").write_text("project(trigeo C)\n")
    (checkout / "include" / "trigeo.h").write_text("/* trigeo */\n")
    _package(checkout / "python")
    _plant(so, shared / "libtrigeo.so", shared / "build" / "libtrigeo.so", tmp_path / "libtrigeo.so")
    r = _import(str(checkout / "python"), cwd=str(tmp_path))
    print(r.stdout, r.stderr[-1500:])
    assert not mark.exists(), f"a planted library was loaded (its constructor ran): {r.stdout} {r.stderr[-800:]}"
    assert r.returncode != 0 and "ImportError" in r.stderr, (r.returncode, r.stderr[-800:])
    assert str(checkout / "build" / "libtrigeo.so") in r.stderr, f"the message names the checkout's build: {r.stderr}"
    assert "TRIGEO_LIB" in r.stderr


@pytest.mark.parametrize("site", ["lib/pkgs", "lib/python3/dist-packages", "lib/python3.11/site-packages"])
def test_installed_package_loads_its_own_library(planted, tmp_path, site):
    """pip's layout: the library inside the package. The old code tried PACKAGE/../../build
    (PREFIX/lib/build for lib/pkgs) before it, and PACKAGE/../../../libtrigeo.so after it."""
    so, mark = planted
    prefix = tmp_path / "prefix"
    pkg = _package(prefix / site)
    here = os.path.join(pkg, "libtrigeo.so")
    shutil.copyfile(_lib.lib_path, here)
    above = [os.path.normpath(os.path.join(pkg, "..", "..", "build", "libtrigeo.so")),
             os.path.normpath(os.path.join(pkg, "..", "..", "..", "libtrigeo.so")),
             str(prefix / "lib" / "build" / "libtrigeo.so")]
    _plant(so, *above)
    r = _import(str(prefix / site), cwd=str(tmp_path))
    print(r.stdout, r.stderr[-1500:])
    assert not mark.exists(), f"a planted library in {above} was loaded: {r.stdout} {r.stderr[-800:]}"
    assert r.returncode == 0 and r.stdout.strip() == here, (r.stdout, r.stderr[-800:], here)


def test_unmarked_install_layout_loads_nothing_above_it(planted, tmp_path):
    """A package without its library in make install's layout but not marked by make install:
    PREFIX/lib/libtrigeo.so is not its library."""
    so, mark = planted
    prefix = tmp_path / "prefix"
    pkg = _package(prefix / "lib" / "python3" / "dist-packages")
    _plant(so, prefix / "lib" / "libtrigeo.so", prefix / "lib" / "python3" / "build" / "libtrigeo.so")
    r = _import(str(prefix / "lib" / "python3" / "dist-packages"), cwd=str(tmp_path))
    print(r.stdout, r.stderr[-1500:])
    assert not mark.exists(), f"a planted library was loaded: {r.stdout} {r.stderr[-800:]}"
    assert r.returncode != 0 and "ImportError" in r.stderr
    assert os.path.join(pkg, "libtrigeo.so") in r.stderr, f"the message names the package's own library: {r.stderr}"


def test_make_install_layout_loads_the_library_beside_it(tmp_path):
    """make install marks the package: PREFIX/lib/libtrigeo.so is then its library (also
    tests/cli_install.sh, on a real staged install)."""
    prefix = tmp_path / "prefix"
    pkg = _package(prefix / "lib" / "python3" / "dist-packages")
    open(os.path.join(pkg, "_installed_beside_lib"), "w").close()
    lib = str(prefix / "lib" / "libtrigeo.so")
    shutil.copyfile(_lib.lib_path, lib)
    r = _import(str(prefix / "lib" / "python3" / "dist-packages"), cwd=str(tmp_path))
    assert r.returncode == 0 and r.stdout.strip() == lib, (r.stdout, r.stderr[-800:], lib)


def test_checkout_build_is_found(tmp_path):
    """A checkout (CMakeLists.txt and include/trigeo.h beside python/) loads its own build/."""
    checkout = tmp_path / "checkout"
    (checkout / "include").mkdir(parents=True)
    (checkout / "CMakeLists.txt").write_text("project(trigeo C)\n")
    (checkout / "include" / "trigeo.h").write_text("/* trigeo */\n")
    _package(checkout / "python")
    (checkout / "build").mkdir()
    lib = str(checkout / "build" / "libtrigeo.so")
    shutil.copyfile(_lib.lib_path, lib)
    r = _import(str(checkout / "python"), cwd=str(tmp_path))
    assert r.returncode == 0 and r.stdout.strip() == lib, (r.stdout, r.stderr[-800:], lib)
