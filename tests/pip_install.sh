#!/bin/bash
# `pip install . --no-build-isolation` from a copy of the repository into a temporary virtual
# environment (with the system's site packages: NumPy, SciPy, setuptools), offline; then, from
# another directory and without PYTHONPATH or TRIGEO_LIB, `import trigeo` must find the
# package and the library built inside it, and run a field. Then the same from a cp -r of that
# copy after configuring a CMake build/ in it (stale caches naming the original folder; the
# issue: pip failed on them deep in a traceback). Skipped (exit 77) only when pip or venv is
# absent. Usage: pip_install.sh REPO [PYTHON]
set -euo pipefail
repo=$1
py=${2:-/usr/bin/python3}
if ! "$py" -m pip --version >/dev/null 2>&1 || ! "$py" -c 'import venv, setuptools, wheel' >/dev/null 2>&1; then
    echo "SKIP: pip, venv, setuptools or wheel missing for $py"
    exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# the sources only: no build directories, no git metadata (pip builds in the tree it is given)
mkdir "$tmp/src"
tar -C "$repo" --exclude='./build*' --exclude='./.git' --exclude='__pycache__' --exclude='*.egg-info' -cf - . |
    tar -C "$tmp/src" -xf -
"$py" -m venv --system-site-packages --without-pip "$tmp/venv"
install() {  # install SOURCES into the virtual environment; pip's output kept for a failure
    if ! CMAKE_BUILD_PARALLEL_LEVEL=${CMAKE_BUILD_PARALLEL_LEVEL:-2} "$tmp/venv/bin/python" -m pip install \
            --no-build-isolation --no-index --no-deps --force-reinstall --quiet "$1" >"$tmp/pip.log" 2>&1; then
        echo "FAIL: pip install $2 ($1):"
        tail -n 40 "$tmp/pip.log"
        exit 1
    fi
}
check() {  # from another directory and without PYTHONPATH or TRIGEO_LIB: import, a field
    mkdir -p "$tmp/elsewhere"
    cd "$tmp/elsewhere"
    env -u PYTHONPATH -u TRIGEO_LIB "$tmp/venv/bin/python" - "$tmp/venv" "$repo/data/nvd_spot.obj" "$1" <<'PY'
import math
import os
import sys

import trigeo
from trigeo import _lib

venv, mesh_path, what = sys.argv[1], sys.argv[2], sys.argv[3]
here = os.path.dirname(trigeo.__file__)
assert here.startswith(venv), f"trigeo imported from {here}, not the virtual environment {venv}"
assert _lib.lib_path == os.path.join(here, "libtrigeo.so"), f"library loaded from {_lib.lib_path}"
mesh = trigeo.load(mesh_path)
d = mesh.field([0])
assert d.shape == (mesh.vertex_count,) and d[0] == 0.0 and all(map(math.isfinite, d)), "field"
m = mesh.distance_matrix([0, 1], max_distance=0.1, sparse=True)
assert m.shape == (2, mesh.vertex_count) and m.nnz > 2, "sparse matrix"
print(f"{what}: pip-installed trigeo {trigeo.version()} from {here}: field max {d.max():.6f}, {m.nnz} sparse entries")
PY
    cd - >/dev/null
}
install "$tmp/src" "a clean copy of the sources"
check "clean sources"
# A copy (cp -r) of a checkout that has a configured CMake build/ and has been pip-installed in
# place (setuptools' build/ beside it): its CMake caches name the original folder, and CMake
# refuses to reuse them from the copy. setup.py builds in a fresh folder of its own instead.
cmake -S "$tmp/src" -B "$tmp/src/build" -DTG_TESTS=OFF -DTG_BENCH=OFF -DTG_FUZZ=OFF >"$tmp/configure.log" 2>&1 ||
    { echo "FAIL: configuring the original checkout"; tail -n 20 "$tmp/configure.log"; exit 1; }
stale=$(find "$tmp/src/build" -name CMakeCache.txt | wc -l)
cp -r "$tmp/src" "$tmp/copy"
touch "$tmp/before-install"
install "$tmp/copy" "a copy of a configured, pip-installed checkout ($stale CMake caches in its build/)"
check "copied checkout with a stale build/"
written=$(find "$tmp/copy" -newer "$tmp/before-install" -name CMakeCache.txt)
if [ -n "$written" ]; then
    echo "FAIL: pip install configured CMake inside the sources: $written"
    exit 1
fi
