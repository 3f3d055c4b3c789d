#!/usr/bin/env bash
# Builds the documentation site: docs/ (Markdown, MyST), the tutorial notebooks with their
# outputs (each executed first with nbconvert into BUILD/docs/notebooks: it needs lubsweep and
# mpirun) and the Python API from lubjoint's docstrings (autodoc, the module built into
# BUILD/python) into BUILD/docs/html with Sphinx, warnings as errors, then checks that it
# works offline (tools/docs/check_site.py: no script from the network, MathJax bundled, the
# notebook's figures in its page). ctest runs it (docs_site).
#   bash tools/docs/site.sh [--build-dir BUILD] [--no-setup] [--no-build] [--no-notebook]
# --no-setup skips tools/setup.sh (Debian packages); --no-build skips building the module and
# lubsweep; --no-notebook shows the notebooks without running them (no outputs: a quick look).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="$root/build"
setup=1
compile=1
notebook=1
while (($#)); do
  case "$1" in
    --build-dir) build="$(cd "$2" && pwd)"; shift 2 ;;
    --no-setup) setup=0; shift ;;
    --no-build) compile=0; shift ;;
    --no-notebook) notebook=0; shift ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) echo "site.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
if ((setup)); then bash "$root/tools/setup.sh"; fi
if ((compile)); then
  if [ ! -f "$build/CMakeCache.txt" ]; then bash "$root/tools/build.sh"; fi
  targets=(_lubjoint)
  if ((notebook)); then targets+=(lubsweep); fi
  cmake --build "$build" -j2 --target "${targets[@]}"
fi
export LUB_PYTHON_DIR="$build/python"
export PYTHONPATH="$build/python${PYTHONPATH:+:$PYTHONPATH}"
export PYTHONDONTWRITEBYTECODE=1
rm -rf "$build/docs/html" "$build/docs/doctrees"
# The notebooks run as a reader runs them (tests/docs/run_notebook.sh), with matplotlib's
# inline backend so that their figures are in the executed copies the pages show.
check_args=()
if ((notebook)); then
  if [ ! -x "$build/sweep/lubsweep" ]; then
    echo "site.sh: the tutorial needs $build/sweep/lubsweep: build it, or pass --no-notebook" >&2
    exit 1
  fi
  export LUB_NOTEBOOK_DIR="$build/docs/notebooks"
  rm -rf "$LUB_NOTEBOOK_DIR"
  for nb in "$root"/docs/tutorials/*.ipynb; do
    (unset MPLBACKEND LUB_SOURCE_DIR
     export PYTHONPATH="$build/python" LUB_BUILD_DIR="$build"
     export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 PYDEVD_DISABLE_FILE_VALIDATION=1
     bash "$root/tests/docs/run_notebook.sh" "$root" "$nb" "$LUB_NOTEBOOK_DIR") >&2
  done
else
  unset LUB_NOTEBOOK_DIR
  check_args+=(--no-notebook)
fi
/usr/bin/python3 -m sphinx -b html -W --keep-going -q -j 1 \
  -d "$build/docs/doctrees" "$root/docs" "$build/docs/html"
/usr/bin/python3 "$root/tools/docs/check_site.py" "${check_args[@]}" "$build/docs/html"
echo "site.sh: $build/docs/html/index.html" >&2
