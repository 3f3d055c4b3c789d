#!/usr/bin/env bash
# Installs missing Debian packages, configures and builds (Release) into build/.
# Warnings are errors when CI=true (or LUB_WERROR=ON).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/tools/setup.sh"
werror="${LUB_WERROR:-OFF}"
if [ "${CI:-}" = "true" ]; then werror=ON; fi
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DLUB_WERROR="$werror" >/dev/null
cmake --build "$root/build" -j "$(nproc)"
