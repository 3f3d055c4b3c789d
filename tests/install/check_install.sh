#!/usr/bin/env bash
# The test install_consumer: `cmake --install` of a build tree into a fresh prefix P, then
# what a downstream user does with P: the consumer project (tests/install) configured with
# -DCMAKE_PREFIX_PATH=P, built and run on one cycle of a scene; P/bin/lubsim --help; the
# man page; `import lubjoint` from P's site-packages with /usr/bin/python3, and the
# message a Python without NumPy gets; P/bin/lubsweep report running P's lubjoint.report.
# Usage: check_install.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
src=$1 build=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
prefix=$work/prefix
step() { echo "install_consumer: $*"; }

step "cmake --install $build --prefix $prefix"
cmake --install "$build" --prefix "$prefix" >"$work/install.log"

step "consumer: configure and build against $prefix"
cmake -S "$src/tests/install" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >"$work/consumer_configure.log"
cmake --build "$work/consumer" -j2 >"$work/consumer_build.log"

step "consumer: one cycle of slider_crank.json"
out=$("$work/consumer/consumer" "$src/configs/scenes/slider_crank.json")
echo "$out"
[ "$out" = "status ok" ] || { echo "install_consumer: expected 'status ok'" >&2; exit 1; }

step "programs and man pages"
for prog in lubsim lubbearing lubsweep; do
  [ -x "$prefix/bin/$prog" ] || { echo "install_consumer: no $prefix/bin/$prog" >&2; exit 1; }
done
"$prefix/bin/lubsim" --help >/dev/null
[ -s "$prefix/share/man/man1/lubsim.1" ] || { echo "install_consumer: no lubsim.1" >&2; exit 1; }

step "import lubjoint from $prefix/lib/python3/dist-packages"
site=$prefix/lib/python3/dist-packages
# From $work, with only P's site-packages added: not the build tree's build/python.
(cd "$work" && PYTHONPATH="$site" PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 -c "
import lubjoint, sys
assert lubjoint.__file__.startswith('$site'), lubjoint.__file__
print('lubjoint', lubjoint.__version__, 'from', lubjoint.__file__)
lubjoint.simulate  # run.py: NumPy and the extension
")
# A Python without NumPy (here /usr/bin/python3 -S: no dist-packages) is told which one to use.
if msg=$(cd "$work" && PYTHONPATH="$site" /usr/bin/python3 -S -c "import lubjoint; lubjoint.simulate" 2>&1); then
  echo "install_consumer: lubjoint.simulate imported without NumPy?" >&2; exit 1
fi
grep -q "built for /usr/bin/python3" <<<"$msg" || { echo "install_consumer: no hint in: $msg" >&2; exit 1; }
echo "wrong Python: $(tail -n 1 <<<"$msg")"

# The installed lubsweep's `report` runs the prefix's lubjoint.report (found beside its bin/,
# no PYTHONPATH): given a file that is no study, that module's message and exit 2, no page.
step "lubsweep report from $prefix"
status=0
msg=$(cd "$work" && env -u PYTHONPATH "$prefix/bin/lubsweep" report "$src/configs/scenes/slider_crank.json" \
      -o "$work/report.html" 2>&1) || status=$?
echo "$msg"
[ "$status" -eq 2 ] && grep -q "slider_crank.json: not an HDF5 file" <<<"$msg" && [ ! -e "$work/report.html" ] ||
  { echo "install_consumer: lubsweep report did not run the prefix's lubjoint.report (exit $status)" >&2; exit 1; }
step "ok"
