#!/usr/bin/env bash
# Installs the Debian packages the project needs, if any is missing.
# Runs `apt-get update` once, and only when something must be installed.
# In a git work tree whose core.hooksPath is unset, enables tools/hooks (commit-msg).
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config git
  libeigen3-dev
  libsundials-dev
  libopenmpi-dev openmpi-bin
  libhdf5-dev hdf5-tools
  nlohmann-json3-dev
  libssl-dev libcli11-dev libfmt-dev
  libgtest-dev libgmock-dev googletest
  libbenchmark-dev
  python3-numpy python3-h5py python3-matplotlib
  python3-xarray python3-h5netcdf python3-pandas python3-pytest
  python3-dev pybind11-dev
  python3-jsonschema python3-jsonpatch
  clang libclang-rt-14-dev clang-tidy
  help2man valgrind
  python3-sphinx python3-myst-parser libjs-mathjax
  python3-nbconvert python3-ipykernel python3-nbformat jupyter-core jupyter-nbconvert
  libjs-chart.js chromium
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update
  $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
else
  echo "setup: all Debian packages present" >&2
fi

# The commit-message rule (tools/hooks/commit-msg, docs/guide/contributing.md) as git's
# commit-msg hook, in a git work tree whose core.hooksPath is not set yet.
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if command -v git >/dev/null && git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  hooks="$(git -C "$root" config --get core.hooksPath || true)"
  if [ -z "$hooks" ]; then
    git -C "$root" config core.hooksPath tools/hooks
    echo "setup: commit messages checked before each commit (git config core.hooksPath tools/hooks)" >&2
  elif [ "$hooks" != "tools/hooks" ]; then
    echo "setup: core.hooksPath is $hooks: tools/hooks/commit-msg not enabled" >&2
  fi
fi
