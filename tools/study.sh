#!/usr/bin/env bash
# The main job: set-up, build, the paper's study on 2 MPI ranks, its summary and figures.
#   writes out/study.h5 (lubsweep configs/grids/paper.json; re-running resumes it; its
#   /boundaries by python3 -m lubjoint.boundaries), out/figures/*.png (tools/plot/paper.py)
#   and out/report.html (lubsweep report), and
#   prints the study's table.
# Exit status: 0 when the study is complete (cases that could not be integrated, e.g. a
# film collapse, are results: recorded in the file and the table); else lubsweep's.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/tools/build.sh"
mkdir -p "$root/out"
cd "$root"

if [ "$(id -u)" -eq 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
mpi_args=(-np 2)
if [ "$(nproc)" -lt 2 ]; then mpi_args+=(--oversubscribe); fi

mpirun "${mpi_args[@]}" build/sweep/lubsweep configs/grids/paper.json -o out/study.h5 --no-summary
# Where the film reaches the safe film (and the cycle loses stability) between grid points,
# stored in the study as /boundaries; the summary prints them (docs/theory/sensitivities.md).
PYTHONPATH="$root/build/python${PYTHONPATH:+:$PYTHONPATH}" \
  /usr/bin/python3 -m lubjoint.boundaries out/study.h5 > /dev/null
echo
build/sweep/lubsweep --summary out/study.h5
echo
PYTHONPATH="$root/build/python${PYTHONPATH:+:$PYTHONPATH}" \
  /usr/bin/python3 tools/plot/paper.py out/study.h5 -o out/figures | sed 's/^/figure: /'
# The whole study as one page a browser opens offline (docs/guide/lubsweep.md).
build/sweep/lubsweep report out/study.h5 -o out/report.html
