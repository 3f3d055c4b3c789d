#!/usr/bin/env bash
# The nightly reproduction: build, run the paper's study (configs/grids/paper.json) on two
# MPI ranks from scratch, compare it with the committed baseline tests/baselines/paper.csv
# (tools/compare/nightly.py: per-metric tolerances, keyed by the cases' axis values), write a
# report (report.md, and report.html: the study and the comparison as a page, lubsweep report).
# docs/validation/nightly.md.
#
#   bash tools/check/nightly.sh              build, run, compare: exit 0 ok, 1 a regression
#                                      (the lines name the case and the metric), 2 bad input
#   bash tools/check/nightly.sh --accept     build, run, and write the baseline from this run
#                                      (review `git diff tests/baselines/paper.csv`, commit)
# Options: --no-build (use the build as it is), --build-dir DIR (default build/),
#          -o DIR (default out/nightly: study.h5, report.md, report.html, a figure per changed case,
#          accepted_study.h5 after --accept, whose series the figures then show beside
#          the new ones), --baseline FILE (default tests/baselines/paper.csv).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
accept=0 build=1 build_dir="$root/build" out="$root/out/nightly" baseline="$root/tests/baselines/paper.csv"
while (($#)); do
  case "$1" in
    --accept) accept=1 ;;
    --no-build) build=0 ;;
    --build-dir) build_dir="$2"; shift ;;
    -o) out="$2"; shift ;;
    --baseline) baseline="$2"; shift ;;
    -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "nightly: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
py=/usr/bin/python3
# compare.py nightly reads the study with lubjoint.study (the build's Python package).
export PYTHONPATH="$build_dir/python${PYTHONPATH:+:$PYTHONPATH}"
if ((build)); then bash "$root/tools/build.sh"; fi
lubsweep="$build_dir/sweep/lubsweep"
[ -x "$lubsweep" ] || { echo "nightly: no $lubsweep (build first, or drop --no-build)" >&2; exit 2; }
mkdir -p "$out"
if [ "$(id -u)" -eq 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
mpi_args=(-np 2)
if [ "$(nproc)" -lt 2 ]; then mpi_args+=(--oversubscribe); fi

# --restart: a nightly always computes every case (resume would reuse rows of the same
# revision, and an uncommitted change keeps the revision).
start=$(date +%s)
mpirun "${mpi_args[@]}" "$lubsweep" "$root/configs/grids/paper.json" -o "$out/study.h5" --restart --no-summary -q
echo "nightly: paper grid run in $(( $(date +%s) - start )) s: $out/study.h5"

if ((accept)); then
  "$py" "$root/tools/compare.py" nightly --accept "$out/study.h5" --baseline "$baseline"
  cp "$out/study.h5" "$out/accepted_study.h5"
  echo "nightly: review with 'git diff $baseline' and commit it"
  exit 0
fi
accepted=()
if [ -f "$out/accepted_study.h5" ]; then accepted=(--accepted-study "$out/accepted_study.h5"); fi
status=0
"$py" "$root/tools/compare.py" nightly "$out/study.h5" --baseline "$baseline" --report "$out" "${accepted[@]}" || status=$?
# The same comparison as a page beside report.md (lubsweep report: lubjoint.report), whatever it found.
if ((status != 2)); then
  "$lubsweep" report "$out/study.h5" -o "$out/report.html" --baseline "$baseline" || status=$((status ? status : $?))
fi
exit "$status"
