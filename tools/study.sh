#!/usr/bin/env bash
# The main job: set-up, build, and the paper's reference case.
# Writes out/run.h5 and prints its summary.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/tools/build.sh"
mkdir -p "$root/out"
"$root/build/core/lubsim" "$root/configs/scenes/slider_crank.json" -o "$root/out/run.h5"
