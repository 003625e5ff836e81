"""Builds the Python package with the project's CMake (`pip install --no-build-isolation .`,
docs/PYTHON.md): configures a Release build in build-python/ (or SKYLIGHT_BUILD_DIR, e.g. an
existing build/ whose extension is then reused), builds the skylight_python target and puts the
extension beside the pure-Python package."""

import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


class CMakeExtension(Extension):
    def __init__(self):
        super().__init__("pyskylight._skylight", sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.environ.get("SKYLIGHT_BUILD_DIR", os.path.join(ROOT, "build-python"))
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            subprocess.check_call([
                "cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                "-DSKYLIGHT_BUILD_TESTS=OFF", "-DSKYLIGHT_BUILD_BENCH=OFF", "-DSKYLIGHT_PYTHON=ON",
                f"-DPython_EXECUTABLE={sys.executable}"])
        subprocess.check_call(["cmake", "--build", build, "--target", "skylight_python"])
        built = os.path.join(build, "python", "pyskylight")
        module = next(f for f in os.listdir(built) if f.startswith("_skylight") and f.endswith(".so"))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(os.path.join(built, module), target)


# setuptools' own build and metadata directories stay under build-python/ (not the CMake build/).
os.makedirs(os.path.join(ROOT, "build-python"), exist_ok=True)
setup(
    options={"build": {"build_base": "build-python/setuptools"},
             "egg_info": {"egg_base": "build-python"}},
    packages=["pyskylight"],
    package_dir={"": "python"},
    package_data={"pyskylight": ["*.pyi", "py.typed"]},
    ext_modules=[CMakeExtension()],
    cmdclass={"build_ext": CMakeBuild},
)
