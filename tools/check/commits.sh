#!/usr/bin/env bash
# Every commit in BASE..HEAD against the commit-message rule of tools/hooks/commit-msg
# (a subject of at most 72 characters, a blank line, a body; a merge: the subject only).
# ctest runs it (lint_commit_messages) from the commit before the rule, ebecac5.
#   bash tools/check/commits.sh BASE
# Exit 0: every commit follows the rule; 1: the offenders are listed; 2: usage;
# 77: BASE is not in this clone (a shallow clone) or this is not a git work tree: skipped.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
hook="$root/tools/hooks/commit-msg"
base="${1:-}"
case "$base" in
  -h|--help) sed -n '2,7p' "$0"; exit 0 ;;
  ""|-*) echo "check_commits: usage: bash tools/check/commits.sh BASE (see --help)" >&2; exit 2 ;;
esac
if ! git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  echo "check_commits: $root is not a git work tree: skipped" >&2
  exit 77
fi
if ! git -C "$root" rev-parse --verify --quiet "$base^{commit}" >/dev/null; then
  echo "check_commits: $base is not in this clone (a shallow clone?): skipped" >&2
  exit 77
fi
msg="$(mktemp)"
trap 'rm -f "$msg"' EXIT
checked=0
offenders=()
while read -r commit parents; do
  mode=--no-merge
  if [ "$(wc -w <<<"$parents")" -gt 1 ]; then mode=--merge; fi
  git -C "$root" log -1 --format=%B "$commit" >"$msg"
  checked=$((checked + 1))
  if ! why="$(bash "$hook" "$mode" "$msg" 2>&1 | head -1)"; then
    offenders+=("$(git -C "$root" log -1 --format='%h %s' "$commit")"$'\n'"    ${why#commit-msg: }")
  fi
done < <(git -C "$root" log --format='%H %P' "$base..HEAD")
if ((${#offenders[@]})); then
  printf '%s\n' "${offenders[@]}"
  echo "check_commits: ${#offenders[@]} of $checked commits in $base..HEAD break the commit-message rule (above)" >&2
  exit 1
fi
echo "check_commits: $checked commits in $base..HEAD follow the commit-message rule"
