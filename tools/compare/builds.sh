#!/usr/bin/env bash
# compare.py builds: do two builds give the same numbers? Runs the same cases with both and
# compares every output file bit for bit (compare.py identical: wall times, the revision and
# which rank ran a case aside) and every printed report (wall times aside). For refactors
# that must change no number.
#   /usr/bin/python3 tools/compare.py builds OLD_BUILD_DIR NEW_BUILD_DIR [--full-factorial]
# Cases: every scene in configs/scenes (hard cases included), the reference scene with
# shooting, auto, error bars, every formulation and four methods (lubsim); the paper grid
# at -np 2 (lubsweep); with --full-factorial also configs/grids/full_factorial.json
# (~4 min a build on 2 cores). Exit 0: identical; 1: differences listed.
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
old="$1"; new="$2"; full="${3:-}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
S="$root/configs/scenes/slider_crank.json"
cases() {  # name, then lubsim arguments
  for s in "$root"/configs/scenes/*.json "$root"/configs/scenes/hard/*.json; do echo "$(basename "$s" .json) $s"; done
  echo "frene_long_shoot $S --set /joints/3/force_law=frene_long --set /simulation/steady=shooting --set /simulation/error_bars=true"
  echo "frene_short_auto $S --set /joints/3/force_law=frene_short --set /simulation/steady=auto"
  echo "printed_auto $S --set /simulation/steady=auto"
  echo "transient_error_bars $S --set /simulation/error_bars=true"
  echo "baumgarte_auto $S --set /solver/formulation=baumgarte --set /simulation/steady=auto"
  echo "partitioned_auto $S --set /solver/formulation=partitioned --set /simulation/steady=auto"
  echo "ggl_ida $S --set /solver/method=ida --set /solver/formulation=ggl"
  echo "arkode_dirk $S --set /solver/method=arkode_dirk --set /joints/3/force_law=frene_long"
  echo "projection $S --set /solver/formulation=baumgarte --set /solver/projection=true"
  echo "difference_quotients $S --set /solver/jacobian=difference_quotients --set /joints/3/force_law=gumbel_long"
}
bad=0
for side in old new; do
  dir="$old"; [ "$side" = new ] && dir="$new"
  mkdir -p "$work/$side"
  cases | while read -r name args; do
    # shellcheck disable=SC2086
    "$dir/core/lubsim" $args -o "$work/$side/$name.h5" > "$work/$side/$name.out" 2>&1
    echo "$name $?" >> "$work/$side/status"
  done
  mpirun -np 2 "$dir/sweep/lubsweep" "$root/configs/grids/paper.json" -o "$work/$side/paper.h5" -q --no-summary
  if [ "$full" = --full-factorial ]; then
    mpirun -np 2 "$dir/sweep/lubsweep" "$root/configs/grids/full_factorial.json" -o "$work/$side/ff.h5" -q --no-summary
  fi
done
diff "$work/old/status" "$work/new/status" || bad=1
for f in "$work"/old/*.h5; do
  n="$(basename "$f")"
  r="$(/usr/bin/python3 "$root/tools/compare.py" identical "$f" "$work/new/$n" | tail -1)"
  [ "$r" = identical ] || { echo "$n: $r"; bad=1; }
done
for f in "$work"/old/*.out; do
  n="$(basename "$f")"
  diff -q <(grep -av "wall_time_s\|^wrote" "$f") <(grep -av "wall_time_s\|^wrote" "$work/new/$n") >/dev/null ||
    { echo "$n: the printed report differs"; bad=1; }
done
[ "$bad" = 0 ] && echo "compare builds: identical ($(ls "$work"/old/*.h5 | wc -l) files)"
exit "$bad"
