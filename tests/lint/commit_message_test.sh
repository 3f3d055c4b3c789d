#!/usr/bin/env bash
# tools/hooks/commit-msg as git's hook and tools/check/commits.sh over a range, in a scratch
# repository: a message that follows the rule commits, a long subject, a second line that is
# not blank and a missing body are refused with the rule named, a merge needs only its
# subject, and the range check lists exactly the commits that skipped the hook.
#   bash tests/lint/commit_message_test.sh SOURCE_DIR
set -euo pipefail
src="$(cd "${1:?usage: commit_message_test.sh SOURCE_DIR}" && pwd)"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
repo="$tmp/repo"
git init -q -b main "$repo"
cd "$repo"
mkdir -p tools/hooks tools/check
cp "$src/tools/hooks/commit-msg" tools/hooks/
cp "$src/tools/check/commits.sh" tools/check/
git config user.name test && git config user.email test@example.invalid
git config core.hooksPath tools/hooks
failed=0
check() {  # check WHAT EXPECTED_EXIT ACTUAL_EXIT [OUTPUT PATTERN]
  if [ "$2" != "$3" ] || { [ $# -gt 4 ] && ! grep -q -- "$5" <<<"$4"; }; then
    echo "FAIL: $1 (exit $3, expected $2)"; echo "$4"; failed=1
  else
    echo "ok: $1"
  fi
}
commit() {  # commit MESSAGE [git commit options]: exit status and output
  local m="$1"; shift
  echo "$RANDOM" >>"file_$(git branch --show-current)" && git add .
  out="$(git commit -q "$@" -F - <<<"$m" 2>&1)" && rc=0 || rc=$?
}
git add tools
commit $'the tools\n\nThe hook and the range check under test.'
check "a message that follows the rule commits" 0 "$rc" "$out"
base="$(git rev-parse HEAD)"
long="$(printf 'x%.0s' {1..73})"
commit "$long"$'\n\nbody'
check "a 73-character subject is refused" 1 "$rc" "$out" "73 characters, more than 72"
commit "$(printf '–%.0s' {1..72})"$'\n\nbody'
check "72 characters (of two bytes and more) commit" 0 "$rc" "$out"
commit $'subject\nsecond line\n\nbody'
check "a second line that is not blank is refused" 1 "$rc" "$out" "second line is not blank"
commit 'subject alone'
check "a message without a body is refused" 1 "$rc" "$out" "no body"
commit $'subject\n\n# a comment git strips\n'
check "a body of comments only is no body" 1 "$rc" "$out" "no body"
commit 'skipped the hook' --no-verify
check "--no-verify commits anyway" 0 "$rc" "$out"
bad="$(git rev-parse --short HEAD)"
git checkout -q -b side HEAD~1
commit $'on a side branch\n\nTo merge it back.'
git checkout -q main
out="$(git merge -q --no-ff --no-edit side 2>&1)" && rc=0 || rc=$?
check "a merge with git's message commits" 0 "$rc" "$out"
out="$(bash tools/check/commits.sh "$base" 2>&1)" && rc=0 || rc=$?
check "the range check lists the commit that skipped the hook" 1 "$rc" "$out" "^$bad skipped the hook"
n="$(grep -c '^[0-9a-f]\{7,\} ' <<<"$out" || true)"
check "and only it" 1 "$n" "$out"
out="$(bash tools/check/commits.sh HEAD~1 2>&1)" && rc=0 || rc=$?
check "a range of good commits and a merge passes" 0 "$rc" "$out"
out="$(bash tools/check/commits.sh 0000000000000000000000000000000000000000 2>&1)" && rc=0 || rc=$?
check "a base not in the clone skips" 77 "$rc" "$out" "not in this clone"
exit "$failed"
