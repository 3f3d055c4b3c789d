#!/usr/bin/env bash
# Executes a tutorial notebook with nbconvert, as a reader would run it from the repository
# (docs/tutorials/index.md): the Debian kernel "python3" (/usr/bin/python3), this build's
# lubjoint on a PYTHONPATH relative to the repository (ctest's, made relative), the
# notebook's own directory as the kernel's working directory, where that relative path does
# not reach (the notebook finds the build itself). The executed copy goes to OUT_DIR; the
# checked-in notebook is not modified. A cell that raises fails the test.
#   bash tests/docs/run_notebook.sh SOURCE_DIR NOTEBOOK OUT_DIR
set -euo pipefail
source_dir="$1"
notebook="$2"
out_dir="$3"
mkdir -p "$out_dir"
cd "$source_dir"
export PYTHONPATH="$(realpath --relative-to="$source_dir" "${PYTHONPATH:-build/python}")"
unset LUB_SOURCE_DIR
jupyter nbconvert --to notebook --execute \
  --ExecutePreprocessor.kernel_name=python3 --ExecutePreprocessor.timeout=240 \
  --output-dir "$out_dir" "$notebook"
echo "run_notebook: $(basename "$notebook") ran; executed copy in $out_dir"
