"""Tacta's PEP 517 build backend: CMake builds the module and plugins, this file writes the wheel.

It needs nothing but the standard library, CMake and a C++ toolchain, so `pip install .` works
offline in any CPython >= 3.9, with or without build isolation: pyenv's and Python 3.12+'s fresh
venvs have no `wheel` or `setuptools` to build with, and Debian's scikit-build is importable from
Debian's python3 alone. The CMake build is the top-level project with TACTA_PYTHON_PACKAGE=ON
(engine, plugins and module; no apps, tests or benchmarks) for the interpreter running pip; the
wheel holds build/python/tacta as it is: the pure-Python files, _tacta*.so (the engine linked in)
and plugins/*.so, which the module searches first.

Settings (pip --config-settings KEY=VALUE, or the environment variable):
  build-dir  TACTA_PIP_BUILD_DIR  CMake build folder (default build-pip/<tag>-<hash of the prefix>,
                                  kept, so a second install rebuilds only what changed)
  jobs       TACTA_PIP_JOBS       parallel build jobs (default: CMAKE_BUILD_PARALLEL_LEVEL or all cores)
  cmake-args TACTA_PIP_CMAKE_ARGS more -D options, separated by spaces
"""
import ast
import base64
import hashlib
import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _project_version():
    text = (ROOT / "CMakeLists.txt").read_text()
    match = re.search(r"project\(\s*tacta\s+VERSION\s+([0-9][0-9.]*)", text)
    if not match:
        raise RuntimeError("CMakeLists.txt: no `project(tacta VERSION x.y.z ...)` to take the version from")
    return match.group(1)


def _toml_value(text):
    # The subset pyproject.toml uses: strings, arrays of strings, booleans, inline tables of strings
    # (tomllib is 3.11+ and this backend runs on 3.9).
    text = re.sub(r"\btrue\b", "True", re.sub(r"\bfalse\b", "False", text))
    text = re.sub(r"([{,]\s*)([A-Za-z0-9_-]+)\s*=", r'\1"\2":', text)
    return ast.literal_eval(text)


def _pyproject():
    """{table: {key: value}} of pyproject.toml."""
    tables, table, pending = {}, None, ""
    for raw in (ROOT / "pyproject.toml").read_text().splitlines():
        line = raw.strip() if not pending else raw
        if not pending and (not line or line.startswith("#")):
            continue
        if not pending and line.startswith("["):
            table = tables.setdefault(line.strip("[] "), {})
            continue
        pending += (" " if pending else "") + line.split(" #")[0].strip()
        if pending.count("[") > pending.count("]") or pending.count("{") > pending.count("}"):
            continue  # an array or table that goes on to the next line
        key, value = pending.split("=", 1)
        table[key.strip().strip('"')] = _toml_value(value.strip())
        pending = ""
    return tables


def _tag():
    version = f"{sys.version_info.major}{sys.version_info.minor}"
    abi = f"cp{version}" + ("t" if sysconfig.get_config_var("Py_GIL_DISABLED") else "")
    abi += "d" if hasattr(sys, "gettotalrefcount") else ""
    platform = re.sub(r"[-.]", "_", sysconfig.get_platform())
    return f"cp{version}-{abi}-{platform}"


def _setting(config_settings, key, env):
    value = (config_settings or {}).get(key)
    return value if value is not None else os.environ.get(env)


def _dist_info_name():
    return f"tacta-{_project_version()}.dist-info"


def _metadata():
    project = _pyproject()["project"]
    lines = ["Metadata-Version: 2.1", f"Name: {project['name']}", f"Version: {_project_version()}",
             f"Summary: {project['description']}", f"Requires-Python: {project['requires-python']}"]
    if "license" in project:
        lines.append(f"License: {project['license']['text']}")
    lines += [f"Classifier: {c}" for c in project.get("classifiers", [])]
    lines += [f"Requires-Dist: {d}" for d in project.get("dependencies", [])]
    optional = _pyproject().get("project.optional-dependencies", {})
    for extra, requirements in optional.items():
        lines.append(f"Provides-Extra: {extra}")
        lines += [f"Requires-Dist: {r}; extra == \"{extra}\"" for r in requirements]
    readme = (ROOT / project["readme"]).read_text() if "readme" in project else ""
    if readme:
        lines.append("Description-Content-Type: text/markdown")
    return "\n".join(lines) + "\n\n" + readme


def _entry_points():
    scripts = _pyproject().get("project.scripts", {})
    if not scripts:
        return ""
    return "[console_scripts]\n" + "".join(f"{name} = {target}\n" for name, target in scripts.items())


def _write_dist_info(directory):
    info = pathlib.Path(directory) / _dist_info_name()
    info.mkdir(parents=True, exist_ok=True)
    (info / "METADATA").write_text(_metadata())
    (info / "WHEEL").write_text(f"Wheel-Version: 1.0\nGenerator: tacta_build\nRoot-Is-Purelib: false\n"
                                f"Tag: {_tag()}\n")
    (info / "entry_points.txt").write_text(_entry_points())
    shutil.copy(ROOT / "LICENSE", info / "LICENSE")
    return info


def _cmake_build(config_settings):
    default = ROOT / "build-pip" / (_tag() + "-" + hashlib.sha256(
        os.path.realpath(sys.base_prefix).encode()).hexdigest()[:8])
    build_dir = pathlib.Path(_setting(config_settings, "build-dir", "TACTA_PIP_BUILD_DIR") or default)
    jobs = _setting(config_settings, "jobs", "TACTA_PIP_JOBS") or \
        os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
    configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir),
                 f"-DPython3_EXECUTABLE={sys.executable}",
                 "-DTACTA_PYTHON_PACKAGE=ON",
                 # The default preset's optimisation without its debug information: the same code,
                 # so a run's state hash equals the command line's (tests/python compare them).
                 "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG",
                 "-DCMAKE_C_FLAGS_RELEASE=-O2 -DNDEBUG"]
    cache = build_dir / "CMakeCache.txt"
    if cache.exists() and f"_Python3_EXECUTABLE:INTERNAL={sys.executable}\n" not in cache.read_text():
        configure.append("-U_Python3_*")  # another interpreter built here: find this one afresh
    if shutil.which("ninja") and not (build_dir / "Makefile").exists():
        configure += ["-G", "Ninja"]
    configure += (_setting(config_settings, "cmake-args", "TACTA_PIP_CMAKE_ARGS") or "").split()
    print("tacta_build:", " ".join(configure), file=sys.stderr, flush=True)
    subprocess.run(configure, check=True, stdout=sys.stderr)
    subprocess.run(["cmake", "--build", str(build_dir), "-j", jobs], check=True, stdout=sys.stderr)
    package = build_dir / "python" / "tacta"
    if not (package / ("_tacta" + sysconfig.get_config_var("EXT_SUFFIX"))).exists():
        raise RuntimeError(f"the build made no module in {package}")
    return package


def _record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}\n"


def get_requires_for_build_wheel(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    return _write_dist_info(metadata_directory).name


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    package = _cmake_build(config_settings)
    with tempfile.TemporaryDirectory() as staging:
        return _write_wheel(package, _write_dist_info(staging), wheel_directory)


def _write_wheel(package, info, wheel_directory):
    name = f"tacta-{_project_version()}-{_tag()}.whl"
    # A build folder shared by two interpreters holds a module for each: take this one's alone.
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    files = sorted(p for p in package.rglob("*") if p.is_file() and "__pycache__" not in p.parts
                   and not (p.name.startswith("_tacta.") and not p.name.endswith(suffix)))
    record = ""
    with zipfile.ZipFile(pathlib.Path(wheel_directory) / name, "w", zipfile.ZIP_DEFLATED) as wheel:
        for path in files:
            arcname = "tacta/" + path.relative_to(package).as_posix()
            data = path.read_bytes()
            wheel.writestr(_zip_info(arcname, path), data)
            record += _record_line(arcname, data)
        for path in sorted(info.iterdir()):
            arcname = f"{info.name}/{path.name}"
            data = path.read_bytes()
            wheel.writestr(_zip_info(arcname, path), data)
            record += _record_line(arcname, data)
        record += f"{info.name}/RECORD,,\n"
        wheel.writestr(_zip_info(f"{info.name}/RECORD", info / "METADATA"), record)
    return name


def _zip_info(arcname, path):
    info = zipfile.ZipInfo(arcname, date_time=(2020, 1, 1, 0, 0, 0))  # reproducible archives
    info.external_attr = (0o755 if os.access(path, os.X_OK) else 0o644) << 16
    info.compress_type = zipfile.ZIP_DEFLATED
    return info
