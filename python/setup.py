"""Build hook of the egw Python package: compiles libegw (the Fortran library with its C
API) with CMake from the repository this directory lives in, and bundles the shared
library inside the package (egw/_lib/libegw.so). No physics is implemented in Python.

Environment:
  EGW_LIBRARY=/path/to/libegw.so   bundle this library instead of building one
  EGW_CMAKE_ARGS="..."             extra arguments for the CMake configure step
"""
import glob
import os
import shlex
import shutil
import subprocess
import tempfile

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)


def _build_library(dest_dir):
    os.makedirs(dest_dir, exist_ok=True)
    given = os.environ.get("EGW_LIBRARY")
    if given:
        shutil.copy2(given, os.path.join(dest_dir, "libegw.so"))
        return
    if not os.path.isfile(os.path.join(REPO, "CMakeLists.txt")):
        raise RuntimeError(
            "egw: the Python package builds libegw from the egw repository it sits in "
            f"({REPO} has no CMakeLists.txt); set EGW_LIBRARY to an installed libegw.so")
    if shutil.which("cmake") is None:
        raise RuntimeError("egw: building libegw needs cmake and gfortran "
                           "(Debian: apt-get install cmake gfortran liblapack-dev libfftw3-dev)")
    with tempfile.TemporaryDirectory(prefix="egw-build-") as build:
        configure = ["cmake", "-S", REPO, "-B", build, "-DEGW_BUILD_STATIC=OFF",
                     "-DCMAKE_BUILD_TYPE=Release"]
        configure += shlex.split(os.environ.get("EGW_CMAKE_ARGS", ""))
        subprocess.run(configure, check=True, stdout=subprocess.DEVNULL)
        subprocess.run(["cmake", "--build", build, "-j", str(os.cpu_count() or 1)],
                       check=True, stdout=subprocess.DEVNULL)
        built = [p for p in glob.glob(os.path.join(build, "libegw.so*"))
                 if not os.path.islink(p)]
        if not built:
            raise RuntimeError("egw: the CMake build produced no libegw.so")
        shutil.copy2(built[0], os.path.join(dest_dir, "libegw.so"))


class BuildWithLibrary(build_py):
    def run(self):
        super().run()
        _build_library(os.path.join(self.build_lib, "egw", "_lib"))


class BinaryDistribution(Distribution):
    def has_ext_modules(self):  # the wheel carries a compiled library: platform tag
        return True


setup(cmdclass={"build_py": BuildWithLibrary}, distclass=BinaryDistribution)
