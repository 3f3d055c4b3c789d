#!/usr/bin/env bash
# No function in core/src or sweep/src over LINES lines (default 100): clang-tidy's
# readability-function-size on every source file, from the build's compile_commands.json.
#   bash tools/check/function_size.sh [BUILD_DIR] [LINES]
# Exit 0: none over; 1: the functions over the limit are listed; 2: no clang-tidy or no
# compile_commands.json.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${1:-$root/build}"
lines="${2:-100}"
command -v clang-tidy >/dev/null || { echo "function_size: clang-tidy not found (tools/setup.sh installs it)" >&2; exit 2; }
[ -f "$build/compile_commands.json" ] || { echo "function_size: no $build/compile_commands.json" >&2; exit 2; }
config="{CheckOptions: [{key: readability-function-size.LineThreshold, value: $lines}]}"
out=$(cd "$root" && find core/src sweep/src -name '*.cpp' | sort |
      xargs -P "$(nproc)" -n 4 clang-tidy -p "$build" --quiet -checks='-*,readability-function-size' \
            -config="$config" 2>/dev/null | grep -A1 "readability-function-size" || true)
if [ -n "$out" ]; then
  echo "$out"
  echo "function_size: functions over $lines lines (above)" >&2
  exit 1
fi
echo "function_size: no function in core/src or sweep/src over $lines lines"
