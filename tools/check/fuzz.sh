#!/usr/bin/env bash
# Fuzzes the scene reader (tests/fuzz/fuzz_scene.cpp) with libFuzzer, AddressSanitizer and
# UndefinedBehaviorSanitizer. Uses clang in its own build directory, build-fuzz/ (the main
# build, build/, stays g++), and starts from the seed corpus configs/scenes/*.json and
# tests/fuzz/corpus/*.
#
#   bash tools/check/fuzz.sh                      # 200000 inputs (LUB_FUZZ_RUNS), about a minute
#   LUB_FUZZ_RUNS=5000000 bash tools/check/fuzz.sh
#   bash tools/check/fuzz.sh -max_total_time=600  # any further arguments go to libFuzzer
#   bash tools/check/fuzz.sh -runs=0              # replay the corpus only
#   LUB_FUZZ_TARGET=grid bash tools/check/fuzz.sh # the grid reader instead (fuzz_grid.cpp; seeds
#                                           # configs/grids/*.json, tests/fuzz/grid_corpus/*)
#
# New interesting inputs accumulate in build-fuzz/fuzz-corpus/; a crashing input is written
# to build-fuzz/fuzz-artifacts/ (reproduce: build-fuzz/tests/fuzz/fuzz_scene FILE). Once it
# is fixed, copy the input into tests/fuzz/corpus/ so ctest's replay (fuzz_scene_replay)
# keeps checking it.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
bash "$root/tools/setup.sh"
build="$root/build-fuzz"
# -O1 -g without -DNDEBUG: Eigen's and the standard library's assertions stay on.
cmake -S "$root" -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" -DLUB_FUZZ=ON -DLUB_BUILD_BENCH=OFF >/dev/null
if [ "${LUB_FUZZ_TARGET:-scene}" = grid ]; then
  cmake --build "$build" -j "$(nproc)" --target fuzz_grid
  mkdir -p "$build/fuzz-grid-corpus" "$build/fuzz-artifacts"
  exec "$build/tests/fuzz/fuzz_grid" -runs="${LUB_FUZZ_RUNS:-20000}" -max_len=4096 -timeout=20 \
    -artifact_prefix="$build/fuzz-artifacts/grid-" -print_final_stats=1 "$@" "$build/fuzz-grid-corpus" \
    "$root/configs/grids" "$root/tests/fuzz/grid_corpus"
fi
cmake --build "$build" -j "$(nproc)" --target fuzz_scene
mkdir -p "$build/fuzz-corpus" "$build/fuzz-artifacts"
exec "$build/tests/fuzz/fuzz_scene" -runs="${LUB_FUZZ_RUNS:-200000}" -max_len=8192 -timeout=10 \
  -dict="$root/tests/fuzz/scene.dict" -artifact_prefix="$build/fuzz-artifacts/" \
  -print_final_stats=1 "$@" "$build/fuzz-corpus" "$root/configs/scenes" "$root/tests/fuzz/corpus"
