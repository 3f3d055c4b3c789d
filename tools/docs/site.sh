#!/usr/bin/env bash
# Builds the documentation site: docs/ (Markdown, MyST) and the Python API from lubjoint's
# docstrings (autodoc, the module built into BUILD/python) into BUILD/docs/html with Sphinx,
# warnings as errors, then checks that it works offline (tools/docs/check_site.py: no script
# from the network, MathJax bundled). ctest runs it (docs_site).
#   bash tools/docs/site.sh [--build-dir BUILD] [--no-setup] [--no-build]
# --no-setup skips tools/setup.sh (Debian packages); --no-build skips building the module.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="$root/build"
setup=1
compile=1
while (($#)); do
  case "$1" in
    --build-dir) build="$(cd "$2" && pwd)"; shift 2 ;;
    --no-setup) setup=0; shift ;;
    --no-build) compile=0; shift ;;
    -h|--help) sed -n '2,6p' "$0"; exit 0 ;;
    *) echo "site.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
if ((setup)); then bash "$root/tools/setup.sh"; fi
if ((compile)); then
  if [ ! -f "$build/CMakeCache.txt" ]; then bash "$root/tools/build.sh"; fi
  cmake --build "$build" -j2 --target _lubjoint
fi
export LUB_PYTHON_DIR="$build/python"
export PYTHONPATH="$build/python${PYTHONPATH:+:$PYTHONPATH}"
export PYTHONDONTWRITEBYTECODE=1
rm -rf "$build/docs/html" "$build/docs/doctrees"
/usr/bin/python3 -m sphinx -b html -W --keep-going -q -j 1 \
  -d "$build/docs/doctrees" "$root/docs" "$build/docs/html"
/usr/bin/python3 "$root/tools/docs/check_site.py" "$build/docs/html"
echo "site.sh: $build/docs/html/index.html" >&2
