"""`pip install .`: the arbor package (python/arbor), its compiled module and the `arbor` program it runs.

The C++ is built by CMake, as for the command line, into build/pip (without tests or benchmarks: minutes on
two cores); or, with ARBOR_BUILD_DIR=DIR, an existing build is packaged as it is (build it first: seconds).
Nothing is downloaded; it works offline with Debian's setuptools and wheel:

    /usr/bin/python3 -m venv --system-site-packages venv
    venv/bin/python -m pip install --no-build-isolation --no-index .
"""

import os
import re
import shutil
import subprocess

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))
BUILD_DIR = os.path.abspath(os.environ.get("ARBOR_BUILD_DIR") or os.path.join(HERE, "build", "pip"))
# setuptools' own staging (build/lib..., *.egg-info), kept inside the build directory rather than in the
# source tree, where `build/` is CMake's.
STAGING = os.path.join(BUILD_DIR, "setuptools")


os.makedirs(STAGING, exist_ok=True)


def project_version():
    """The version of CMakeLists.txt's project(), the one source of arbor.__version__'s release part."""
    with open(os.path.join(HERE, "CMakeLists.txt")) as f:
        match = re.search(r"project\(arbor VERSION ([0-9.]+)", f.read())
    if not match:
        raise RuntimeError("CMakeLists.txt: no `project(arbor VERSION X.Y ...)` to take the version from")
    return match.group(1)


class CMakeBuild(build_ext):
    """Builds the module and the program with CMake, then copies them into the package."""

    def run(self):
        build_dir = BUILD_DIR
        # A given build is not rebuilt here: its binaries may be in use (the tests run them while one of them
        # installs the package), and relinking them under a running program is not this command's business.
        if not os.environ.get("ARBOR_BUILD_DIR"):
            if not os.path.exists(os.path.join(build_dir, "CMakeCache.txt")):
                generator = ["-G", "Ninja"] if shutil.which("ninja") else []
                subprocess.run(["cmake", "-S", HERE, "-B", build_dir, *generator, "-DCMAKE_BUILD_TYPE=Release",
                                "-DARBOR_BUILD_TESTS=OFF", "-DARBOR_BUILD_BENCH=OFF", "-DARBOR_PYTHON=ON"],
                               check=True)
            subprocess.run(["cmake", "--build", build_dir, "--target", "arbor_python", "arbor",
                            "-j", str(os.cpu_count() or 1)], check=True)
        package = os.path.join(build_dir, "python", "arbor")
        modules = [name for name in (os.listdir(package) if os.path.isdir(package) else [])
                   if name.startswith("_arbor.") and name.endswith(".so")]
        if len(modules) != 1:
            raise RuntimeError(f"{package}: expected one compiled _arbor module, found {modules or 'none'} "
                               "(is ARBOR_BUILD_DIR a build with the Python module, built?)")
        target = self.get_ext_fullpath("arbor._arbor")
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy2(os.path.join(package, modules[0]), target)
        # arbor.smooth, sweep, convert and cli run the program of the same build (arbor.executable()).
        program = os.path.join(os.path.dirname(target), "bin", "arbor")
        os.makedirs(os.path.dirname(program), exist_ok=True)
        shutil.copy2(os.path.join(build_dir, "bin", "arbor"), program)


setup(
    name="arbor",
    version=project_version(),
    description="Landmark SLAM research framework: FastSLAM, map back ends, association strategies",
    python_requires=">=3.10",
    install_requires=["numpy"],
    package_dir={"": "python"},
    packages=["arbor"],
    py_modules=["arbor_files"],
    package_data={"arbor": ["__init__.pyi", "py.typed"]},
    ext_modules=[Extension("arbor._arbor", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
    options={"build": {"build_base": STAGING}, "egg_info": {"egg_base": STAGING}},
)
