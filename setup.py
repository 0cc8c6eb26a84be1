"""The C++ extension of `pip install .` (metadata: pyproject.toml): CMake builds the target
_pronk, and the built module is copied into the wheel. PRONK_BUILD_DIR names an existing
CMake build tree to take it from (built there if needed, unless PRONK_PREBUILT=1); otherwise a fresh Release tree under
build-pip/ is configured for the interpreter pip runs."""
import glob
import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
os.makedirs(os.path.join(ROOT, "build-pip"), exist_ok=True)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        tree = os.environ.get("PRONK_BUILD_DIR")
        if tree:
            tree = os.path.abspath(tree)
        else:
            tree = os.path.join(ROOT, "build-pip", "cmake")
            subprocess.check_call(["cmake", "-S", ROOT, "-B", tree, "-DCMAKE_BUILD_TYPE=Release",
                                   "-DPRONK_BUILD_TESTS=OFF",
                                   "-DPython_EXECUTABLE=" + sys.executable])
        # PRONK_PREBUILT=1 (the test suite's pip test): take the module as built, never build
        # in a tree whose other tests are running.
        if os.environ.get("PRONK_PREBUILT") != "1":
            jobs = str(os.cpu_count() or 1)
            subprocess.check_call(["cmake", "--build", tree, "--target", "_pronk", "-j", jobs])
        built = glob.glob(os.path.join(tree, "python", "pronk", "_pronk*.so"))
        if len(built) != 1:
            raise RuntimeError(f"pronk: expected one _pronk*.so in {tree}/python/pronk, found {built}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    ext_modules=[Extension("pronk._pronk", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own scratch space, apart from the CMake trees in build/.
    options={"build": {"build_base": "build-pip"}, "egg_info": {"egg_base": "build-pip"}},
)
