"""The part of `pip install .` that pyproject.toml cannot say: the extension stengmc._core is
built by the project's CMake (python/CMakeLists.txt), not by setuptools' compiler driver, so
it gets the flags, the sources and the libraries the tests check bit for bit against the
command line. Only the module's targets are built (no tests, no executable).

Where CMake builds: build-python/ beside build/ (one level below the source like it, so
ccache, with CCACHE_BASEDIR at or above the clone, reuses build/'s objects of the same
sources), or $STENGMC_PYTHON_BUILD_DIR. Extra configure options: $STENGMC_CMAKE_ARGS.
$STENGMC_PYTHON_CONFIGURED_BUILD_DIR names a build tree already configured with the module
(the test suite's build/): it is not configured again, only its module target brought up to
date, so the install test does not compile the library a third time.
Compile jobs: $CMAKE_BUILD_PARALLEL_LEVEL (CMake's own variable), every core by default."""
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = Path(__file__).resolve().parent


def project_version():
    """The one version (CHANGELOG.md): CMakeLists.txt's project(stengmc VERSION x.y.z)."""
    text = (SOURCE / "CMakeLists.txt").read_text()
    found = re.search(r"project\(\s*stengmc\s+VERSION\s+([0-9]+\.[0-9]+\.[0-9]+)", text)
    if not found:
        sys.exit("setup.py: no `project(stengmc VERSION x.y.z)` in CMakeLists.txt")
    return found.group(1)


class CMakeBuild(build_ext):
    """Configures the project with the Python module on, for the interpreter running this
    (a venv's or the system's), builds target stengmc_python and copies _core where
    setuptools packs the extension."""

    def build_extension(self, ext):
        if shutil.which("cmake") is None:
            sys.exit("setup.py: building stengmc needs CMake >= 3.25 (Debian: apt-get install cmake; "
                     "or bash scripts/setup.sh for every package the build needs)")
        configured = os.environ.get("STENGMC_PYTHON_CONFIGURED_BUILD_DIR")
        build_dir = Path(configured or os.environ.get("STENGMC_PYTHON_BUILD_DIR", SOURCE / "build-python")).resolve()
        if configured and not (build_dir / "CMakeCache.txt").is_file():
            sys.exit(f"setup.py: STENGMC_PYTHON_CONFIGURED_BUILD_DIR={configured} holds no configured CMake build (no CMakeCache.txt)")
        configure = [
            "cmake", "-S", str(SOURCE), "-B", str(build_dir),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DSTENGMC_WITH_PYTHON=ON",
            "-DSTENGMC_BUILD_TESTS=OFF",
            # The interpreter that runs pip: its headers, its extension suffix, and what
            # pybind11 builds for (FindPython; pybind11 follows Python3 once it is found).
            f"-DPython3_EXECUTABLE={sys.executable}",
            *shlex.split(os.environ.get("STENGMC_CMAKE_ARGS", "")),
        ]
        if not configured:
            subprocess.run(configure, check=True)
        build = ["cmake", "--build", str(build_dir), "--target", "stengmc_python"]
        if "CMAKE_BUILD_PARALLEL_LEVEL" not in os.environ:
            build += ["-j", str(os.cpu_count() or 1)]
        subprocess.run(build, check=True)

        built = sorted((build_dir / "python" / "stengmc").glob("_core*.so"))
        suffix = Path(self.get_ext_filename(ext.name)).name.removeprefix("_core")
        matching = [path for path in built if path.name == "_core" + suffix]
        if not matching:
            sys.exit(f"setup.py: CMake built {[p.name for p in built]} in {build_dir / 'python/stengmc'}, "
                     f"not _core{suffix} for {sys.executable}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(matching[0], target)


setup(
    version=project_version(),
    # No sources: CMake compiles them. The entry tells setuptools the wheel holds a compiled
    # module (a platform wheel, cp311-cp311-linux_x86_64) and where it goes.
    ext_modules=[Extension("stengmc._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own build/ would be inside CMake's build/ (the developer build); keep apart.
    options={"build": {"build_base": "build-python/setuptools"}},
)
