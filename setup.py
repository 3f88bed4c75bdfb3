"""Builds the package's compiled parts with the project's CMake: the module softdrop/_core and the
`softdrop` program, which the package carries (softdrop/bin/softdrop) and installs as a command.

The CMake build directory is $SOFTDROP_BUILD_DIR, or build/ in the source tree: a tree the
scripts already built is reused, and only what changed is compiled again.
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = pathlib.Path(__file__).resolve().parent


def version():
    text = (SOURCE / "CMakeLists.txt").read_text()
    return re.search(r"project\(softdrop VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(os.environ.get("SOFTDROP_BUILD_DIR", SOURCE / "build")).resolve()
        if not (build / "CMakeCache.txt").exists():  # a new tree: the release build, for this Python
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.run(["cmake", "-S", str(SOURCE), "-B", str(build), *generator, "-DCMAKE_BUILD_TYPE=Release",
                            "-DSOFTDROP_PYTHON=ON", f"-DPYTHON_EXECUTABLE={sys.executable}"], check=True)
        # (a configured tree is only built: CMake configures it again if its lists changed)
        jobs = str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(build), "--target", "_core", "softdrop", "--parallel", jobs], check=True)
        core = next((build / "python" / "softdrop").glob("_core*.so"), None)
        if core is None:
            raise RuntimeError(f"{build}: the CMake build made no Python module (is pybind11-dev installed?)")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(core, target)
        # Its stub, which the build writes from python/softdrop/_core.pyi.in and the droplet's fields.
        shutil.copy2(build / "python" / "softdrop" / "_core.pyi", target.parent / "_core.pyi")
        program = target.parent / "bin" / "softdrop"
        program.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(build / "softdrop", program)


# setuptools' own files go under build/, not into the source tree.
STAGING = SOURCE / "build" / "python-package"
STAGING.mkdir(parents=True, exist_ok=True)
setup(version=version(), ext_modules=[Extension("softdrop._core", sources=[])], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": str(STAGING)}, "egg_info": {"egg_base": str(STAGING)}})
