"""Builds libtrigeo.so with CMake (the shared library target only, Release) and puts it inside
the trigeo package, where trigeo/_lib.py finds it; everything else is in pyproject.toml.

    pip install . --no-build-isolation      # offline: Debian's python3-pip and python3-setuptools

CMAKE_BUILD_PARALLEL_LEVEL sets the build's jobs (default: the machine's cores)."""
import os
import re
import shutil
import subprocess

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))


def version() -> str:
    with open(os.path.join(HERE, "include", "trigeo.h"), encoding="utf-8") as f:
        text = f.read()
    parts = [re.search(rf"#define TG_VERSION_{k} (\d+)", text).group(1) for k in ("MAJOR", "MINOR", "PATCH")]
    return ".".join(parts)


class BuildWithLibrary(build_py):
    """build_py, then the C library: configured in build_temp, copied into the built package."""

    def run(self):
        super().run()
        temp = os.path.join(os.path.abspath(self.get_finalized_command("build").build_temp), "libtrigeo")
        subprocess.check_call(["cmake", "-S", HERE, "-B", temp, "-DCMAKE_BUILD_TYPE=Release", "-DTG_TESTS=OFF",
                               "-DTG_BENCH=OFF", "-DTG_FUZZ=OFF", "-DTG_SANITIZE=OFF"])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.check_call(["cmake", "--build", temp, "--target", "trigeo_shared", "-j", jobs])
        target = os.path.join(self.build_lib, "trigeo", "libtrigeo.so")
        shutil.copyfile(os.path.join(temp, "libtrigeo.so"), target)  # the file, not the symlink


class BinaryDistribution(Distribution):
    """The wheel holds a compiled library: tag it for this platform, not py3-none-any."""

    def has_ext_modules(self):
        return True


setup(version=version(), cmdclass={"build_py": BuildWithLibrary}, distclass=BinaryDistribution)
