#!/usr/bin/env bash
# CTest `python_pip_install`: installs the Python package with pip, as docs/python.md tells a
# user (a fresh venv over Debian's packages, no index, no build isolation), taking the module
# from this build tree (PRONK_BUILD_DIR), then runs examples/ from outside the source tree
# against the installed package.
#   scripts/pip_install_test.sh SOURCE_DIR BUILD_DIR PYTHON
set -euo pipefail
src=$1 build=$2 python=$3
work=$build/pip-install-test
rm -rf "$work" && mkdir -p "$work"
"$python" -m venv --system-site-packages "$work/venv"
# Offline, as on a machine without an index (this one may point pip at local wheels). The
# module as this tree built it (PRONK_PREBUILT): a test never rebuilds the tree it tests (a
# stale tree rebuilt mid-suite would hand the other tests a module of another commit).
env -u PIP_FIND_LINKS PRONK_BUILD_DIR="$build" PRONK_PREBUILT=1 PIP_NO_CACHE_DIR=1 \
  "$work/venv/bin/pip" install --no-build-isolation --no-index "$src" > "$work/pip.log" 2>&1 ||
  { cat "$work/pip.log"; exit 1; }
cd "$work"  # not the source tree: `import pronk` must find the installed package
where=$("$work/venv/bin/python" -c "import pronk; print(pronk.__file__)")
case "$where" in
  "$work/venv/"*) echo "pronk imported from $where" ;;
  *) echo "pronk imported from $where, not from the venv" >&2; exit 1 ;;
esac
# Read pip's whole answer first: grep -q in a pipe would end early and break pip's pipe.
show=$("$work/venv/bin/pip" show pronk)
grep -q '^Requires: numpy' <<< "$show" || { echo "numpy not declared: $show" >&2; exit 1; }
MPLBACKEND=Agg "$work/venv/bin/python" "$src/examples/notebook_simulate_plot.py" "$work/nb.png"
test -s "$work/nb.png"
"$work/venv/bin/python" "$src/examples/scipy_minimize.py" --maxiter 20
"$work/venv/bin/python" "$src/examples/optuna_study2.py" --help > /dev/null
echo "pip install: ok"
