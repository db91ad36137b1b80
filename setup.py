"""The emnet wheel, built by CMake: `pip install --no-build-isolation .` or `pip wheel ...`.

The package's Python files are python/emnet/; its compiled module (_emnet), the command line
program and the ngspice worker are targets of the CMake build in build/ (the directory
tools/build uses, configured as it does when it is not yet: Release, Ninja), so that after
tools/build the wheel takes seconds. EMNET_CMAKE_BUILD_DIR names another build directory.
The wheel holds emnet/_emnet*.so and emnet/bin/{emnet, emnet-ngspice-worker}; the console
script `emnet` runs emnet/bin/emnet. The version is the project() version of CMakeLists.txt,
the one the library reports.
"""

import glob
import os
import re
import shutil
import subprocess
import sys

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

ROOT = os.path.dirname(os.path.abspath(__file__))
PROGRAMS = ("emnet", "emnet-ngspice-worker")


def project_version():
    """MAJOR.MINOR.PATCH from CMakeLists.txt's `project(emnet VERSION ...)`."""
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as cmake_lists:
        match = re.search(r"project\(emnet\s+VERSION\s+([0-9.]+)", cmake_lists.read())
    if not match:
        sys.exit("setup.py: no `project(emnet VERSION ...)` in CMakeLists.txt")
    return match.group(1)


def cmake_build_directory():
    return os.path.abspath(os.environ.get("EMNET_CMAKE_BUILD_DIR") or os.path.join(ROOT, "build"))


def run(command):
    print("setup.py:", " ".join(command), flush=True)
    if subprocess.call(command) != 0:
        sys.exit(f"setup.py: failed: {' '.join(command)} (tools/setup-deps installs what the "
                 "build needs)")


def build_with_cmake(build):
    """The compiled module and the programs, built (or found up to date) in `build`."""
    if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
        run(["cmake", "-S", ROOT, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
             f"-DPYTHON_EXECUTABLE={sys.executable}"])
    run(["cmake", "--build", build, "-j", str(os.cpu_count() or 1), "--target", "_emnet",
         *PROGRAMS])


class BuildWithCMake(build_py):
    """build_py, then the CMake targets' files copied into the package being built."""

    def run(self):
        super().run()
        build = cmake_build_directory()
        build_with_cmake(build)
        package = os.path.join(self.build_lib, "emnet")
        modules = glob.glob(os.path.join(build, "python", "emnet", "_emnet*.so"))
        if len(modules) != 1:
            sys.exit(f"setup.py: expected one compiled module in {build}/python/emnet, "
                     f"found {modules}")
        shutil.copy2(modules[0], package)
        os.makedirs(os.path.join(package, "bin"), exist_ok=True)
        for program in PROGRAMS:
            shutil.copy2(os.path.join(build, program), os.path.join(package, "bin", program))


class BinaryDistribution(Distribution):
    """A wheel for this platform and Python (it holds compiled code), not a pure one."""

    def has_ext_modules(self):
        return True


os.makedirs(os.path.join(ROOT, "build", "setuptools"), exist_ok=True)  # egg_base must exist
setup(
    version=project_version(),
    packages=["emnet"],
    package_dir={"": "python"},
    package_data={"emnet": ["py.typed", "*.pyi"]},
    cmdclass={"build_py": BuildWithCMake},
    distclass=BinaryDistribution,
    options={"build": {"build_base": os.path.join("build", "setuptools")},
             "egg_info": {"egg_base": os.path.join("build", "setuptools")}},
    zip_safe=False,
)
