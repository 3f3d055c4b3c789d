#!/usr/bin/env bash
# The test command: set-up, build, and every test suite (ctest), slow ones excluded
# unless LUB_SLOW=1 (see docs/validation/test-suite.md).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/tools/build.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$root/build"
if [ "${LUB_SLOW:-0}" = "1" ]; then
  ctest --output-on-failure -j "$(nproc)" "$@"
else
  ctest --output-on-failure -j "$(nproc)" -LE slow "$@"
fi
