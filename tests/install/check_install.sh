#!/usr/bin/env bash
# The test install_consumer: `cmake --install` of a build tree into a fresh prefix P, then
# what a downstream user does with P (docs/guide/install.md): the C++-only consumer project
# (tests/install) configured with -DCMAKE_PREFIX_PATH=P, built and run on one cycle of an
# installed example scene; P/share/lubjoint (configs/ with the schema, docs/); the installed
# programs' --help and errors naming files that exist there; the man page; `import lubjoint`
# with /usr/bin/python3 from PYTHONPATH=P/lib/python3.X/dist-packages, the line the install
# prints, and the message a Python without NumPy gets; P/bin/lubsweep report running P's
# lubjoint.report.
# Usage: check_install.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
src=$1 build=$2 work=$3
rm -rf "$work"
mkdir -p "$work/prefix"
prefix=$(realpath "$work/prefix")  # as the programs see themselves (/proc/self/exe)
unset LUBJOINT_DATADIR
share=$prefix/share/lubjoint
step() { echo "install_consumer: $*"; }
fail() { echo "install_consumer: $*" >&2; exit 1; }

step "cmake --install $build --prefix $prefix"
cmake --install "$build" --prefix "$prefix" >"$work/install.log"

step "share/lubjoint: configs/ (scenes, grids, schema) and docs/ as in the repository"
for dir in configs docs; do
  # Every example file and every Markdown page (docs/conf.py, Sphinx's, is not installed).
  missing=$(cd "$src/$dir" && find . -type f \( -name '*.json' -o -name '*.md' \) | sort |
            while read -r f; do [ -f "$share/$dir/$f" ] || echo "$f"; done)
  [ -z "$missing" ] || fail "not in $share/$dir: $missing"
done
[ -s "$share/configs/scene.schema.json" ] || fail "no scene schema"
/usr/bin/python3 -c "import json, sys; json.load(open(sys.argv[1]))['\$schema']" "$share/configs/scene.schema.json"
echo "$(find "$share/configs" -name '*.json' | wc -l) files in configs/, $(find "$share/docs" -name '*.md' | wc -l) pages in docs/"

step "consumer (project(... CXX)): configure and build against $prefix"
cmake -S "$src/tests/install" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >"$work/consumer_configure.log"
# The package enabled no C language behind the project's back.
! grep -q '^CMAKE_C_COMPILER:' "$work/consumer/CMakeCache.txt" || fail "the consumer has a C compiler"
cmake --build "$work/consumer" -j2 >"$work/consumer_build.log"

step "consumer: one cycle of the installed slider_crank.json"
out=$("$work/consumer/consumer" "$share/configs/scenes/slider_crank.json")
echo "$out"
[ "$out" = "status ok" ] || fail "expected 'status ok'"

step "programs and man pages"
for prog in lubsim lubbearing lubsweep; do
  [ -x "$prefix/bin/$prog" ] || fail "no $prefix/bin/$prog"
done
[ -s "$prefix/share/man/man1/lubsim.1" ] || fail "no lubsim.1"

step "the installed programs name files of $share, and they exist"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # lubsweep: a singleton MPI process
help=$("$prefix/bin/lubsim" --help; "$prefix/bin/lubsweep" --help)
# An error from the library (the scene reader): a $schema that is not a string.
sed 's|"\$schema": "[^"]*"|"$schema": 1|' "$share/configs/scenes/slider_crank.json" >"$work/bad_schema.json"
if err=$("$prefix/bin/lubsim" --check "$work/bad_schema.json" 2>&1); then fail "bad \$schema accepted"; fi
named=$(grep -o "$share/[^ ;,)]*" <<<"$help
$err" | sed 's/\.$//' | sort -u)
for f in configs/scene.schema.json configs/scenes/ configs/grids/ docs/guide/grids.md; do
  grep -qx "$share/$f" <<<"$named" || fail "the help or error names no $share/$f: $named"
done
while read -r p; do [ -e "$p" ] || fail "named but not installed: $p"; done <<<"$named"
echo "$(wc -l <<<"$named") paths named, all present"

# The directory as docs/guide/install.md derives it: its `export PYTHONPATH=P/...` line, P filled in.
line=$(grep -m1 '^export PYTHONPATH=P/' "$src/docs/guide/install.md") || fail "no PYTHONPATH line in install.md"
site=$(export PYTHONPATH=; eval "${line/=P\//=$prefix/}"; echo "$PYTHONPATH")
xy=$(/usr/bin/python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])')
[ "$site" = "$prefix/lib/python$xy/dist-packages" ] || fail "install.md derives $site"
step "import lubjoint from $site"
# The default prefix's directory is one /usr/bin/python3 searches (Debian: /usr/local/lib/...).
/usr/bin/python3 -c "import site, sys; assert sys.argv[1] in site.getsitepackages(), site.getsitepackages()" \
  "/usr/local/lib/python$xy/dist-packages"
# The install prints the one line another prefix needs.
grep -qF "export PYTHONPATH=$site" "$work/install.log" || fail "no 'export PYTHONPATH=$site' in install.log"
# From $work, with only P's site-packages added: not the build tree's build/python.
(cd "$work" && PYTHONPATH="$site" PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 -c "
import lubjoint, sys
assert lubjoint.__file__.startswith('$site'), lubjoint.__file__
print('lubjoint', lubjoint.__version__, 'from', lubjoint.__file__)
lubjoint.simulate  # run.py: NumPy and the extension
")
# A Python without NumPy (here /usr/bin/python3 -S: no dist-packages) is told which one to use.
if msg=$(cd "$work" && PYTHONPATH="$site" /usr/bin/python3 -S -c "import lubjoint; lubjoint.simulate" 2>&1); then
  fail "lubjoint.simulate imported without NumPy?"
fi
grep -q "built for /usr/bin/python3" <<<"$msg" || fail "no hint in: $msg"
echo "wrong Python: $(tail -n 1 <<<"$msg")"

# The installed lubsweep's `report` runs the prefix's lubjoint.report (found beside its bin/,
# no PYTHONPATH): given a file that is no study, that module's message and exit 2, no page.
step "lubsweep report from $prefix"
status=0
msg=$(cd "$work" && env -u PYTHONPATH "$prefix/bin/lubsweep" report "$src/configs/scenes/slider_crank.json" \
      -o "$work/report.html" 2>&1) || status=$?
echo "$msg"
[ "$status" -eq 2 ] && grep -q "slider_crank.json: not an HDF5 file" <<<"$msg" && [ ! -e "$work/report.html" ] ||
  fail "lubsweep report did not run the prefix's lubjoint.report (exit $status)"
step "ok"
