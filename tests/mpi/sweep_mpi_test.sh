#!/usr/bin/env bash
# MPI tests of lubsweep, run by ctest (label mpi). Usage:
#   sweep_mpi_test.sh CASE MPIEXEC LUBSWEEP STUDY_COMPARE WORKDIR
# CASE: ranks     -np 1 and -np 2 give bit-identical results, in the same order
#       resume    a sweep killed after 3 cases (SIGKILL on rank 0) resumes to the same
#                 results as an uninterrupted run, running only the missing cases
#       bad_input a bad grid exits 2 under mpirun, one message, and creates no file; an
#                 existing non-study output is refused and left untouched; a study of
#                 another grid is refused (exit 2, untouched) unless --drop-other-cases
#       abort     on_failure = abort stops the sweep (exit 3, incomplete file); a re-run
#                 completes it, the failure kept
#       lock      a second sweep on the output of a running one is refused (exit 2, naming
#                 the first: pid and host) and changes nothing; the first is unharmed; a
#                 killed sweep's stale lock file does not block the next sweep
#       output_path  lubsweep and lubsim refuse an output path that is a directory (or in
#                 a missing directory) before any work: exit 2, message, no file created
#       one_cycle a grid of one-cycle cases (cheap_4096.json in small) costs one period a
#                 case in the study grids' steady method (auto) and in continuation; exit 77
#                 (skipped) without Debian's h5py
#       tools     the Python tools on a small study (compare.py study finds a regression,
#                 plot/paper.py and plot/sweep_map.py draw); exit 77 (skipped) without Debian's
#                 h5py, matplotlib, xarray, h5netcdf, pandas
set -euo pipefail
what="$1" mpiexec="$2" lubsweep="$3" compare="$4" work="$5"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
grid="$here/tiny_grid.json"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
rm -rf "$work" && mkdir -p "$work" && cd "$work"
run() {  # run NP OUT [args...]
  local np="$1" out="$2"; shift 2
  "$mpiexec" -np "$np" "$lubsweep" "$grid" -o "$out" --no-summary "$@"
}
fail() { echo "FAIL: $*" >&2; exit 1; }

case "$what" in
ranks)
  run 1 np1.h5
  run 2 np2.h5
  "$compare" np1.h5 np2.h5
  ;;
resume)
  run 2 full.h5
  set +e
  LUBSWEEP_TEST_KILL_AFTER=3 run 2 killed.h5 2> killed.log
  rc=$?
  set -e
  [ "$rc" -ne 0 ] || fail "the killed sweep exited 0"
  rows=$(h5ls killed.h5/cases/case | sed -E 's/.*\{([0-9]+)\/.*/\1/')
  [ "$rows" = "3" ] || fail "the killed file holds $rows rows, expected 3"
  run 2 killed.h5 2> resumed.log
  grep -q "holds 3 of them (7 to run)" resumed.log || { cat resumed.log >&2; fail "the resumed sweep did not skip the 3 cases done"; }
  "$compare" full.h5 killed.h5
  # Once complete, a re-run runs nothing and changes no result.
  run 1 killed.h5 2> again.log
  grep -q "holds 10 of them (0 to run)" again.log || { cat again.log >&2; fail "the complete study was run again"; }
  "$compare" full.h5 killed.h5
  ;;
bad_input)
  set +e
  "$mpiexec" -np 2 "$lubsweep" "$here/bad_grid.json" -o bad.h5 2> bad.log
  rc=$?
  set -e
  [ "$rc" -eq 2 ] || { cat bad.log >&2; fail "a bad grid exited $rc, expected 2"; }
  # The grid's path and value, then the scene parser's rule on the journal radius it sets.
  grep -q "grid.axes\[0\].values\[1\] = -0.0001: gives an invalid scene (joint rod_slider: journal_radius_m = bearing_radius_m - clearance = 0.01 m - -0.0001 m): joints\[3\].journal_radius_m = 0.0101: must be < bearing_radius_m = 0.01 m (the radial clearance must be > 0)" bad.log || { cat bad.log >&2; fail "message"; }
  [ ! -e bad.h5 ] || fail "a bad grid created its output file"
  # One message, from rank 0 only; every rank left MPI through MPI_Finalize (Open MPI 4
  # still adds its own box after any non-zero exit status: docs/guide/lubsweep.md).
  [ "$(grep -c '^lubsweep: ' bad.log)" = 1 ] || { cat bad.log >&2; fail "the message is not printed once"; }
  ! grep -q "without calling \"finalize\"\|MPI_ABORT\|exited on signal" bad.log || { cat bad.log >&2; fail "a rank did not leave MPI cleanly"; }
  # A study file of another grid is refused, untouched, naming the cases it would lose;
  # --drop-other-cases drops them.
  run 2 ten.h5 2> ten.log
  cp ten.h5 ten_before.h5
  sed 's/"values": \[5000, 500, 50\]/"values": [5000, 500]/; s|"\.\./\.\./configs|"'"$here"'/../../configs|' "$grid" > smaller.json
  set +e
  "$mpiexec" -np 2 "$lubsweep" smaller.json -o ten.h5 --no-summary 2> smaller.log
  rc=$?
  set -e
  [ "$rc" -eq 2 ] || { cat smaller.log >&2; fail "a file of a larger grid: exit $rc, expected 2"; }
  grep -q "ten.h5: the file holds 3 computed cases that are not cases of the grid smaller.json: case_0002 (force_law=ideal speed_rpm=50 solver.rtol=1e-06)" smaller.log \
    || { cat smaller.log >&2; fail "the refusal does not name the cases"; }
  cmp -s ten.h5 ten_before.h5 || fail "a refused study file was changed"
  "$mpiexec" -np 2 "$lubsweep" smaller.json -o ten.h5 --no-summary --drop-other-cases 2> drop.log \
    || { cat drop.log >&2; fail "--drop-other-cases was refused"; }
  grep -q "dropping 3 rows" drop.log || { cat drop.log >&2; fail "--drop-other-cases: no dropping line"; }
  echo "not a study" > other.h5
  set +e
  "$mpiexec" -np 2 "$lubsweep" "$grid" -o other.h5 2> other.log
  rc=$?
  set -e
  [ "$rc" -eq 2 ] || { cat other.log >&2; fail "a foreign output file: exit $rc, expected 2"; }
  [ "$(cat other.h5)" = "not a study" ] || fail "a foreign output file was overwritten"
  ;;
abort)
  # on_failure = abort: the sweep stops after the failed case (exit 3) with a resumable,
  # incomplete file; a re-run keeps the recorded failure and completes the rest.
  set +e
  "$mpiexec" -np 2 "$lubsweep" "$here/abort_grid.json" -o a.h5 --no-summary 2> abort.log
  rc=$?
  set -e
  [ "$rc" -eq 3 ] || { cat abort.log >&2; fail "an aborted sweep exited $rc, expected 3"; }
  grep -q "on_failure = abort: stopping" abort.log || { cat abort.log >&2; fail "no abort message"; }
  rows=$(h5ls a.h5/cases/case | sed -E 's/.*\{([0-9]+)\/.*/\1/')
  [ "$rows" -lt 8 ] || fail "the aborted sweep ran every case"
  [ "$(h5dump -A -a /complete a.h5 | grep -Eo '\(0\): [0-9]+')" = "(0): 0" ] || fail "the aborted file is marked complete"
  "$mpiexec" -np 2 "$lubsweep" "$here/abort_grid.json" -o a.h5 --no-summary 2> again.log \
    || { cat again.log >&2; fail "the resumed sweep failed (complete with one recorded failure: exit 0)"; }
  grep -q "holds 1 of them" again.log || grep -q "holds 2 of them" again.log || { cat again.log >&2; fail "resume"; }
  [ "$(h5dump -A -a /complete a.h5 | grep -Eo '\(0\): [0-9]+')" = "(0): 1" ] || fail "the resumed file is not complete"
  ;;
lock)
  "$mpiexec" -np 2 "$lubsweep" "$here/long_grid.json" -o held.h5 --no-summary 2> first.log &
  first=$!
  for _ in $(seq 1 300); do [ -s held.h5.lock ] && break; sleep 0.1; done
  [ -s held.h5.lock ] || { cat first.log >&2; fail "the first sweep wrote no lock file"; }
  set +e
  "$mpiexec" -np 2 "$lubsweep" "$grid" -o held.h5 --no-summary 2> second.log
  rc=$?
  set -e
  kill -0 "$first" 2>/dev/null || { cat first.log >&2; fail "the first sweep ended before the second tried (the test needs a longer grid)"; }
  [ "$rc" -eq 2 ] || { cat second.log >&2; fail "a second sweep on a held output exited $rc, expected 2"; }
  grep -q "held.h5: the file is in use by another sweep (pid [0-9]* on host $(hostname)" second.log \
    || { cat second.log >&2; fail "the refusal does not name the file, the other sweep's pid and host"; }
  ! grep -q "not an HDF5 file" second.log || fail "HDF5's own locking error leaked"
  kill "$first"
  wait "$first" || true
  # The killed sweep's lock file is stale (flock ends with its process): the next sweep
  # takes it over, resumes the file, and removes the lock when it ends. It runs another
  # (the tiny) grid, so the long grid's rows are dropped with consent (--drop-other-cases).
  run 2 held.h5 --drop-other-cases 2> third.log || { cat third.log >&2; fail "a sweep after a killed one was refused"; }
  [ ! -e held.h5.lock ] || fail "the lock file outlived the sweep"
  ;;
output_path)
  mkdir -p adir
  for out in adir/ adir missing_dir/s.h5; do
    set +e
    "$mpiexec" -np 2 "$lubsweep" "$grid" -o "$out" 2> out.log
    rc=$?
    set -e
    [ "$rc" -eq 2 ] || { cat out.log >&2; fail "lubsweep -o $out exited $rc, expected 2"; }
    grep -q "lubsweep: -o $out: " out.log || { cat out.log >&2; fail "lubsweep -o $out: message"; }
    cat out.log >> all.log
  done
  grep -q "its directory missing_dir does not exist" out.log || { cat out.log >&2; fail "missing directory message"; }
  lubsim="$(dirname "$lubsweep")/../core/lubsim"
  scene="$here/../../configs/scenes/slider_crank.json"
  for out in adir/ adir missing_dir/r.h5; do
    set +e
    start=$(date +%s%N)
    "$lubsim" "$scene" -o "$out" -q 2> sim.log
    rc=$?
    ms=$(( ($(date +%s%N) - start) / 1000000 ))
    set -e
    [ "$rc" -eq 2 ] || { cat sim.log >&2; fail "lubsim -o $out exited $rc, expected 2"; }
    grep -q "lubsim: -o $out: " sim.log || { cat sim.log >&2; fail "lubsim -o $out: message"; }
    [ "$ms" -lt 1000 ] || fail "lubsim -o $out took $ms ms: it ran before refusing"
    cat sim.log >> all.log
  done
  [ "$(grep -c "must name a file, not a directory (the path ends in '/')" all.log)" = 2 ] || { cat all.log >&2; fail "directory message"; }
  [ "$(grep -c "must name a file, not a directory (it is an existing directory)" all.log)" = 2 ] || { cat all.log >&2; fail "existing directory message"; }
  [ -z "$(ls -A adir)" ] || fail "a refused output created files in adir: $(ls -A adir)"
  [ ! -e missing_dir ] || fail "a refused output created its directory"
  ;;
one_cycle)
  /usr/bin/python3 -c "import h5py" 2>/dev/null || { echo "no h5py: skipped"; exit 77; }
  grid="$here/one_cycle_grid.json"
  run 1 one.h5
  /usr/bin/python3 - <<'PY' || fail "a one-cycle case integrated more than one period"
import h5py, sys
c = h5py.File("one.h5", "r")["cases"]
periods, cycles = c["periods_integrated"][()], c["cycles_run"][()]
print(f"{len(periods)} cases, periods_integrated {sorted(set(periods.tolist()))}, cycles_run {sorted(set(cycles.tolist()))}")
sys.exit(0 if len(periods) == 8 and (periods == 1).all() and (cycles == 1).all() else 1)
PY
  ;;
tools)
  # The Python post-processing on a small study (skipped without Debian's h5py/matplotlib).
  py=/usr/bin/python3
  tools="$here/../../tools"
  "$py" -c "import h5py, matplotlib, numpy, xarray, h5netcdf, pandas" 2>/dev/null || { echo "no h5py/matplotlib/xarray/h5netcdf/pandas: skipped"; exit 77; }
  run 2 s.h5
  "$py" "$tools/compare.py" study s.h5 s.h5 -q
  cp s.h5 worse.h5
  "$py" - <<'PY'
import h5py, math
with h5py.File("worse.h5", "r+") as f:
    # A case with a steady cycle (the others have no steady metrics to change: NaN).
    i = next(i for i, c in enumerate(f["cases/classification"][()]) if c.decode() == "periodic")
    f["cases/peak_reaction_N"][i] *= 1.01
    open("edited", "w").write(f["cases/name"][i].decode())
PY
  set +e
  "$py" "$tools/compare.py" study worse.h5 s.h5 -q > compare.log
  rc=$?
  set -e
  [ "$rc" -eq 1 ] || { cat compare.log >&2; fail "compare.py study missed a 1 % change of peak_reaction_N (exit $rc)"; }
  grep -q "REGRESSION $(cat edited): peak_reaction_N" compare.log || { cat compare.log >&2; fail "compare.py study message"; }
  "$py" "$tools/plot/paper.py" s.h5 -o figures > figures.log
  [ -s figures/fig05_reference.png ] || fail "plot/paper.py drew no reference figure"
  "$py" "$tools/plot/sweep_map.py" s.h5 -x speed_rpm -y force_law --fix solver.rtol=1e-6 -m max_eps -m steps -o maps > maps.log
  [ -s maps/map_max_eps_speed_rpm_force_law.png ] || fail "plot/sweep_map.py drew no map"
  ;;
*)
  fail "unknown test $what"
  ;;
esac
echo "sweep_mpi_test $what: ok"
