"""Builds libtrigeo.so with CMake (the shared library target only, Release) and puts it inside
the trigeo package, where trigeo/_lib.py finds it; everything else is in pyproject.toml.

    pip install . --no-build-isolation      # offline: Debian's python3-pip and python3-setuptools

CMAKE_BUILD_PARALLEL_LEVEL sets the build's jobs (default: the machine's cores)."""
import os
import re
import shutil
import subprocess
import tempfile

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

try:
    from setuptools.errors import ExecError
except ImportError:  # setuptools before 59
    from distutils.errors import DistutilsExecError as ExecError

HERE = os.path.dirname(os.path.abspath(__file__))


def version() -> str:
    with open(os.path.join(HERE, "include", "trigeo.h"), encoding="utf-8") as f:
        text = f.read()
    parts = [re.search(rf"#define TG_VERSION_{k} (\d+)", text).group(1) for k in ("MAJOR", "MINOR", "PATCH")]
    return ".".join(parts)


class BuildWithLibrary(build_py):
    """build_py, then the C library: configured and built by CMake in a fresh temporary folder of
    its own, removed afterwards (kept after a failure, for CMake's logs), and copied into the
    built package. Never a build folder that
    came with the sources: a copy of a checkout carries its CMake caches, which name the
    original folder, and CMake refuses them (a stale cache from elsewhere); nor is anything left
    in the sources."""

    def run(self):
        # the package's own output folder starts empty: no file of an earlier build (copied along
        # with the sources) reaches the wheel
        shutil.rmtree(os.path.join(self.build_lib, "trigeo"), ignore_errors=True)
        super().run()
        temp = tempfile.mkdtemp(prefix="trigeo-cmake-")
        self._cmake(["cmake", "-S", HERE, "-B", temp, "-DCMAKE_BUILD_TYPE=Release", "-DTG_TESTS=OFF",
                     "-DTG_BENCH=OFF", "-DTG_FUZZ=OFF", "-DTG_SANITIZE=OFF"], "configure", temp)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        self._cmake(["cmake", "--build", temp, "--target", "trigeo_shared", "-j", jobs], "build", temp)
        target = os.path.join(self.build_lib, "trigeo", "libtrigeo.so")
        shutil.copyfile(os.path.join(temp, "libtrigeo.so"), target)  # the file, not the symlink
        shutil.rmtree(temp, ignore_errors=True)

    @staticmethod
    def _cmake(args, what, temp):
        """One CMake step; a failure is one line naming the step (CMake's own output is above it)
        and the build folder, kept for CMake's logs (a new one is made on the next try)."""
        try:
            rc = subprocess.call(args)
        except OSError as e:
            shutil.rmtree(temp, ignore_errors=True)
            raise ExecError(f"trigeo: cannot run cmake ({e.strerror}): install CMake (3.25 or later) and a C compiler")
        if rc != 0:
            raise ExecError(f"trigeo: CMake could not {what} libtrigeo.so (exit {rc}; its messages are above, its "
                            f"logs in {temp}): {' '.join(args)}")


class BinaryDistribution(Distribution):
    """The wheel holds a compiled library: tag it for this platform, not py3-none-any."""

    def has_ext_modules(self):
        return True


setup(version=version(), cmdclass={"build_py": BuildWithLibrary}, distclass=BinaryDistribution)
