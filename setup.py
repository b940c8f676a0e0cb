"""The build behind pyproject.toml: CMake builds the extension, the plugins and the library
(from Debian's packages, no downloads), `cmake --install` stages them, and the wheel takes the
package from the stage plus the library and plugins as data under <prefix>/lib, where the
installed module looks for them (python/CMakeLists.txt, python/s2sim/__init__.py).

Environment:
    S2SIM_CMAKE_BUILD_DIR  a configured CMake build folder to build in (default: build/pip,
                           configured with the release settings and without tests/benchmarks)
    S2SIM_CMAKE_ARGS       more arguments for the configure step (space-separated)
    S2SIM_BUILD_JOBS       parallel jobs (default 2)
"""

import os
import re
import shutil
import subprocess

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))


def version():
    with open(os.path.join(HERE, "sdk", "include", "s2sim", "version.hpp")) as f:
        text = f.read()
    parts = [re.search(r"#define S2SIM_SDK_VERSION_%s (\d+)" % p, text).group(1)
             for p in ("MAJOR", "MINOR", "PATCH")]
    return ".".join(parts)


BUILD_DIR = os.path.abspath(os.environ.get("S2SIM_CMAKE_BUILD_DIR")
                            or os.path.join(HERE, "build", "pip"))
STAGE = os.path.join(BUILD_DIR, "pip-stage")
os.makedirs(BUILD_DIR, exist_ok=True)  # setuptools' egg_info writes there before the build


def run(*command):
    print("+", " ".join(command), flush=True)
    subprocess.run(command, check=True)


class CMakeBuild(build_py):
    """Builds with CMake, stages the install, and adds the staged package to the build."""

    def run(self):
        cmake = os.environ.get("CMAKE_COMMAND", "cmake")
        if not os.path.exists(os.path.join(BUILD_DIR, "CMakeCache.txt")):
            run(cmake, "-S", HERE, "-B", BUILD_DIR, "-DCMAKE_BUILD_TYPE=Release",
                "-DS2SIM_BUILD_TESTS=OFF", "-DS2SIM_BUILD_BENCH=OFF", "-DS2SIM_BUILD_PYTHON=ON",
                "-DPython_EXECUTABLE=/usr/bin/python3",
                *os.environ.get("S2SIM_CMAKE_ARGS", "").split())
        run(cmake, "--build", BUILD_DIR, "-j", os.environ.get("S2SIM_BUILD_JOBS", "2"))
        shutil.rmtree(STAGE, ignore_errors=True)
        run(cmake, "--install", BUILD_DIR, "--prefix", STAGE)
        super().run()
        package = os.path.join(STAGE, "lib", "python3", "dist-packages", "s2sim")
        target = os.path.join(self.build_lib, "s2sim")
        shutil.copytree(package, target, dirs_exist_ok=True)
        # The library and the plugins go to <prefix>/lib: from the installed module
        # (<prefix>/lib/pythonX.Y/site-packages/s2sim) that is three folders up, as installed
        # by CMake.
        lib = os.path.join(STAGE, "lib")
        files = [("lib", sorted(os.path.join(lib, n) for n in os.listdir(lib)
                                if n.startswith("libs2sim.so")))]
        plugins = os.path.join(lib, "s2sim", "plugins")
        files.append(("lib/s2sim/plugins", sorted(os.path.join(plugins, n)
                                                  for n in os.listdir(plugins))))
        self.distribution.data_files = [(d, f) for d, f in files if f]


class BinaryDistribution(Distribution):
    """A wheel for this platform and interpreter: it holds a compiled module."""

    def has_ext_modules(self):
        return True


setup(
    version=version(),
    packages=["s2sim"],
    package_dir={"s2sim": "python/s2sim"},
    cmdclass={"build_py": CMakeBuild},
    distclass=BinaryDistribution,
    # setuptools' own folders beside CMake's, not in the source tree.
    options={"build": {"build_base": os.path.join(BUILD_DIR, "setuptools")},
             "egg_info": {"egg_base": BUILD_DIR}},
    zip_safe=False,
)
