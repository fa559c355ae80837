"""CoverBench's PEP 517 build backend, standard library only: `pip install ./python` builds the
compiled part (the CMake target coverbench_python, pybind11) in the source tree's build folder
and writes a wheel holding python/coverbench and that module. pip needs nothing from PyPI
(pyproject.toml: ``requires = []``).

The build folder: ``--config-settings build-dir=DIR``, else COVERBENCH_BUILD_DIR, else build/
(the one scripts/setup.sh builds; relative paths are from the source tree's root). A folder that
is not configured yet is configured as setup.sh does (Release, Ninja when installed) for the
Python that runs pip; one that is reuses what is built, so a second install compiles nothing. A
folder built for another Python version is refused with the way out: another folder.

Wheels and the editable install (``pip install -e ./python``) are built; an sdist is not (the
package is built from the source tree, whose C++ is outside python/).
"""
from __future__ import annotations

import base64
import hashlib
import os
import shutil
import subprocess
import sys
import sysconfig
import tomllib
import zipfile
from typing import Any, Dict, List, Mapping, Optional, Tuple

PYTHON_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROOT = os.path.dirname(PYTHON_DIR)
PACKAGE = "coverbench"
TARGET = "coverbench_python"
# Every file in a wheel gets this date (zip's earliest, 1980-01-01): the same tree gives the same
# wheel, byte for byte, whatever the files' times.
ZIP_DATE = (1980, 1, 1, 0, 0, 0)


def _log(message: str) -> None:
    print(f"coverbench_build: {message}", file=sys.stderr, flush=True)


def _project() -> Dict[str, Any]:
    with open(os.path.join(PYTHON_DIR, "pyproject.toml"), "rb") as f:
        project: Dict[str, Any] = tomllib.load(f)["project"]
    return project


def _tag() -> str:
    """The wheel's tag: this interpreter, its ABI and platform (cp311-cp311-linux_x86_64)."""
    if sys.implementation.name != "cpython":
        raise RuntimeError(f"coverbench builds for CPython, not {sys.implementation.name}")
    version = f"{sys.version_info.major}{sys.version_info.minor}"
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"cp{version}-cp{version}{sys.abiflags}-{platform}"


def _build_dir(config_settings: Optional[Mapping[str, Any]]) -> str:
    chosen = (config_settings or {}).get("build-dir") or os.environ.get("COVERBENCH_BUILD_DIR") or "build"
    return os.path.normpath(os.path.join(ROOT, str(chosen)))


def _python() -> str:
    """The interpreter the module is built for: the one running pip, outside any virtual
    environment (a venv may be deleted; the build folder outlives it)."""
    base = getattr(sys, "_base_executable", None) or sys.executable
    return os.path.realpath(base)


def _run(cmd: List[str]) -> None:
    _log(" ".join(cmd))
    # The build's output goes to stderr: pip shows it with -v, or when the build fails.
    done = subprocess.run(cmd, stdout=sys.stderr, stderr=sys.stderr)
    if done.returncode != 0:
        raise RuntimeError(f"`{' '.join(cmd)}` failed with exit code {done.returncode} (its output is above)")


def _compiled(config_settings: Optional[Mapping[str, Any]]) -> str:
    """Builds the target coverbench_python and returns the module's path."""
    if not os.path.isfile(os.path.join(ROOT, "CMakeLists.txt")):
        raise RuntimeError(f"{ROOT}: not CoverBench's source tree (no CMakeLists.txt): install from the source "
                           "tree's python/ folder")
    cmake = shutil.which("cmake")
    if cmake is None:
        raise RuntimeError("cmake is not installed: run `bash scripts/setup.sh` (it installs the build's Debian "
                           "packages), or install cmake")
    build = _build_dir(config_settings)
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    module = os.path.join(build, "python", PACKAGE, "_core" + suffix)
    if not os.path.isfile(os.path.join(build, "CMakeCache.txt")):
        configure = [cmake, "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release", f"-DCOVERBENCH_PYTHON={_python()}"]
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        _run(configure)
    else:
        others = [n for n in _listdir(os.path.join(build, "python", PACKAGE))
                  if n.startswith("_core.") and n.endswith(".so") and n != "_core" + suffix]
        if others and not os.path.isfile(module):
            raise RuntimeError(f"{build} builds the module for another Python ({others[0]}), not for "
                               f"{sys.executable} (_core{suffix}): install with another build folder, "
                               "e.g. `pip install ./python --config-settings build-dir=build-py` or "
                               "COVERBENCH_BUILD_DIR=build-py")
    jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
    _run([cmake, "--build", build, "--target", TARGET, "-j", jobs])
    if not os.path.isfile(module):
        raise RuntimeError(f"{module}: not built (the build folder's Python is not {sys.executable}?)")
    return module


def _listdir(path: str) -> List[str]:
    return sorted(os.listdir(path)) if os.path.isdir(path) else []


def _metadata() -> str:
    p = _project()
    lines = ["Metadata-Version: 2.1", f"Name: {p['name']}", f"Version: {p['version']}",
             f"Summary: {p['description']}", f"License: {p['license']['text']}",
             f"Requires-Python: {p['requires-python']}"]
    for extra, requirements in sorted(p.get("optional-dependencies", {}).items()):
        lines.append(f"Provides-Extra: {extra}")
        lines += [f'Requires-Dist: {r}; extra == "{extra}"' for r in requirements]
    return "\n".join(lines) + "\n"


def _dist_info() -> str:
    p = _project()
    return f"{p['name']}-{p['version']}.dist-info"


def _wheel_file(tag: str) -> str:
    return f"Wheel-Version: 1.0\nGenerator: coverbench_build\nRoot-Is-Purelib: false\nTag: {tag}\n"


def _write_wheel(wheel_directory: str, tag: str, files: List[Tuple[str, bytes, int]]) -> str:
    """Writes the wheel from (archive name, content, mode) and the dist-info; returns its name."""
    p = _project()
    dist_info = _dist_info()
    files = sorted(files) + [(f"{dist_info}/METADATA", _metadata().encode(), 0o644),
                             (f"{dist_info}/WHEEL", _wheel_file(tag).encode(), 0o644)]
    record = []
    for name, data, _ in files:
        digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
        record.append(f"{name},sha256={digest},{len(data)}")
    record.append(f"{dist_info}/RECORD,,")
    files.append((f"{dist_info}/RECORD", ("\n".join(record) + "\n").encode(), 0o644))
    wheel_name = f"{p['name']}-{p['version']}-{tag}.whl"
    path = os.path.join(wheel_directory, wheel_name)
    with zipfile.ZipFile(path + ".part", "w", compression=zipfile.ZIP_DEFLATED) as z:
        for name, data, mode in files:
            info = zipfile.ZipInfo(name, date_time=ZIP_DATE)
            info.external_attr = (0o100000 | mode) << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, data)
    os.replace(path + ".part", path)
    return wheel_name


def _package_files() -> List[Tuple[str, bytes, int]]:
    """python/coverbench's sources, the stub and the marker of typed packages."""
    out = []
    folder = os.path.join(PYTHON_DIR, PACKAGE)
    for name in _listdir(folder):
        if name.endswith((".py", ".pyi")) or name == "py.typed":
            with open(os.path.join(folder, name), "rb") as f:
                out.append((f"{PACKAGE}/{name}", f.read(), 0o644))
    return out


# --- PEP 517 ------------------------------------------------------------------------------------
def get_requires_for_build_wheel(config_settings: Optional[Mapping[str, Any]] = None) -> List[str]:
    return []


def get_requires_for_build_editable(config_settings: Optional[Mapping[str, Any]] = None) -> List[str]:
    return []


def build_wheel(wheel_directory: str, config_settings: Optional[Mapping[str, Any]] = None,
                metadata_directory: Optional[str] = None) -> str:
    module = _compiled(config_settings)
    compiled = []
    # The module, and the plug-ins it opens from its own folder (base/include/coverbench/plugin.hpp;
    # built with the module): GDAL when a config imports walls, OMPL for a sampling transit or a car
    # that reverses.
    build = os.path.dirname(os.path.dirname(os.path.dirname(module)))
    for path in (module, *(os.path.join(build, f"libcoverbench_{name}.so") for name in ("gdal", "ompl"))):
        with open(path, "rb") as f:
            compiled.append((f"{PACKAGE}/{os.path.basename(path)}", f.read(), 0o755))
    name = _write_wheel(wheel_directory, _tag(), _package_files() + compiled)
    _log(f"wrote {name}")
    return name


def build_editable(wheel_directory: str, config_settings: Optional[Mapping[str, Any]] = None,
                   metadata_directory: Optional[str] = None) -> str:
    """PEP 660: a wheel with a .pth naming python/; the package finds its compiled part in the
    build folder (COVERBENCH_BUILD_DIR at import, default build/), as in the source tree."""
    build = _build_dir(config_settings)
    if build != os.path.join(ROOT, "build"):
        _log(f"note: the editable package imports the module from {build} only when COVERBENCH_BUILD_DIR names it")
    _compiled(config_settings)
    pth = (f"{PACKAGE}_editable.pth", (PYTHON_DIR + "\n").encode(), 0o644)
    name = _write_wheel(wheel_directory, _tag(), [pth])
    _log(f"wrote {name} (editable: {PYTHON_DIR})")
    return name


def build_sdist(sdist_directory: str, config_settings: Optional[Mapping[str, Any]] = None) -> str:
    raise RuntimeError("coverbench has no sdist: its C++ is outside python/; install from the source tree "
                       "(`pip install ./python`)")
