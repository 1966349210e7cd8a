#!/bin/sh
# The pip package as a user installs it: `pip install .` (offline, no build isolation) into a
# fresh venv, then the Python suite against the installed package, run from outside the source
# tree with no PYTHONPATH, so `import tacta` can only find the venv's copy.
# usage: package_test.sh SOURCE_DIR WORK_DIR PYTHON   (ctest python_package)
set -eu
src=$1 work=$2 python=$3
unset PYTHONPATH
rm -rf "$work/venv"
mkdir -p "$work"
"$python" -m venv --system-site-packages "$work/venv"
py="$work/venv/bin/python"
start=$(date +%s)
# build-dir kept between runs (an incremental rebuild); a fresh clone builds from nothing.
"$py" -m pip install --no-build-isolation --no-deps --no-index --disable-pip-version-check -q \
  --config-settings "build-dir=$work/cmake" "$src"
echo "pip install: $(( $(date +%s) - start )) s"
cd "$work"
"$py" - "$work/venv" <<'PY'
import os, sys
import tacta
venv = os.path.realpath(sys.argv[1])
where = os.path.realpath(tacta.__file__)
assert where.startswith(venv), f"tacta imported from {where}, not the venv {venv}"
found = tacta.plugins()
own = os.path.join(os.path.dirname(where), "plugins")
assert os.path.realpath(found["search_paths"][0]) == own, found["search_paths"]
assert all(os.path.realpath(p["file"]).startswith(own) for p in found["loaded"]), found["loaded"]
assert not found["refused"], found["refused"]
print(f"tacta {tacta.__version__} from {where}: {len(found['loaded'])} plugins from {own}")
PY
exec "$py" -m pytest "$src/tests/python" -q -p no:cacheprovider
