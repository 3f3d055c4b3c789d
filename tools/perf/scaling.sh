#!/usr/bin/env bash
# The sweep's parallel efficiency on this machine and its scaling beyond it (issue 16):
#   1. the full factorial (transient only, as issue 16 measured it) and the 4096 cheap cases,
#      each at -np 1 and -np 2, one after the other: wall, case time, efficiency;
#   2. bench_sweep_overhead (mpirun -np 2): the coordinator's cost per result, the message
#      round trip, bytes per case and rank 0's memory;
#   3. tools/perf/scaling_model.py fed with both: predicted efficiency at 1-1024 ranks, checked
#      against the -np 2 runs.
# Writes out/scaling/ (the study files, overhead.json, model_*.json). Takes ~4 minutes.
#   bash tools/perf/scaling.sh [--no-build]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
if [ "${1:-}" != "--no-build" ]; then bash "$root/tools/build.sh"; fi
cd "$root"
export PYTHONPATH="$root/build/python${PYTHONPATH:+:$PYTHONPATH}"  # lubjoint.study reads the studies
out=out/scaling
mkdir -p "$out"
if [ "$(id -u)" -eq 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
over=()
if [ "$(nproc)" -lt 2 ]; then over=(--oversubscribe); fi

# The full factorial with the transient method only (issue 16's baseline; lubsweep's
# default, auto, shoots periodic orbits and takes ~20x longer).
/usr/bin/python3 - "$root" "$out/full_factorial_transient.json" <<'PY'
import json, os, sys
root, dst = sys.argv[1], sys.argv[2]
g = json.load(open(os.path.join(root, "configs/grids/full_factorial.json")))
g["scene"] = os.path.join(root, "configs/scenes/slider_crank.json")
g.setdefault("set", {})["/simulation/steady"] = "transient"
json.dump(g, open(dst, "w"), indent=1)
PY

declare -A wall
for grid in "$out/full_factorial_transient.json" configs/grids/cheap_4096.json; do
  name=$(basename "$grid" .json)
  for np in 1 2; do
    f="$out/${name}_np$np.h5"
    s=$(date +%s.%N)
    mpirun -np $np "${over[@]}" build/sweep/lubsweep "$grid" -o "$f" --restart -q --no-summary
    e=$(date +%s.%N)
    wall[$name,$np]=$(/usr/bin/python3 -c "print(f'{$e - $s:.2f}')")
  done
  /usr/bin/python3 - "$out/${name}_np1.h5" "${wall[$name,1]}" "$out/${name}_np2.h5" "${wall[$name,2]}" "$name" <<'PY'
import sys
from lubjoint import study  # the one reader of study files (build/python)
f1, w1, f2, w2, name = sys.argv[1], float(sys.argv[2]), sys.argv[3], float(sys.argv[4]), sys.argv[5]
c1 = study.cases(f1)["wall_time_s"].sum()
c2 = study.cases(f2)["wall_time_s"].sum()
print(f"{name}: -np 1 {w1:.2f} s (case time {c1:.2f} s), -np 2 {w2:.2f} s (case time {c2:.2f} s); "
      f"efficiency T1/(2 T2) = {w1 / (2 * w2):.3f}; at the same per-case speed "
      f"(T1 c2/c1)/(2 T2) = {w1 * c2 / c1 / (2 * w2):.3f}")
PY
done

mpirun -np 2 "${over[@]}" build/tests/bench/bench_sweep_overhead configs/grids/cheap_4096.json --cases 0 | tee "$out/overhead.json"

for name in full_factorial_transient cheap_4096; do
  echo "== $name"
  /usr/bin/python3 tools/perf/scaling_model.py "$out/${name}_np1.h5" --overhead "$out/overhead.json" \
    --wall1 "${wall[$name,1]}" --measured "2=${wall[$name,2]}" \
    --check "2=$out/${name}_np2.h5:${wall[$name,2]}" --json "$out/model_$name.json"
done
echo "== cheap_4096 x 25 (102 400 cases)"
/usr/bin/python3 tools/perf/scaling_model.py "$out/cheap_4096_np1.h5" --overhead "$out/overhead.json" \
  --wall1 "${wall[cheap_4096,1]}" --replicate 25 --json "$out/model_cheap_4096_x25.json"
