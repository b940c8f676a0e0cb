#!/usr/bin/env bash
# docs/architecture.md names every file of kernel/src once, in its folder's table of
# "`kernel/src`, file by file", and names no file that is gone.
#   tests/docs/architecture_files_test.sh [ROOT]
set -euo pipefail
root="${1:-$(cd "$(dirname "$0")/../.." && pwd)}"
doc="$root/docs/architecture.md"
fail=0
# The tables: from the section's heading to the next "## " heading; each folder's table follows
# its **`folder/`** line.
section="$(awk '/^### `kernel\/src`, file by file/{on=1; next} on && /^## /{exit} on' "$doc")"
if [[ -z "$section" ]]; then
  echo "architecture_files_test: $doc has no section '### \`kernel/src\`, file by file'"
  exit 1
fi
listed="$(printf '%s\n' "$section" | awk '
  /^\*\*`[a-z_]+\/`\*\*/ { folder = $0; sub(/^\*\*`/, "", folder); sub(/\/`.*/, "", folder); next }
  /^\| `/ && folder != "" {
    cell = $0; sub(/^\| /, "", cell); sub(/ \|.*/, "", cell)
    n = split(cell, names, /, /)
    for (i = 1; i <= n; i++) { name = names[i]; gsub(/`/, "", name); print folder "/" name }
  }')"
for f in $(cd "$root/kernel/src" && find . -type f | sed 's|^\./||' | sort); do
  count="$(printf '%s\n' "$listed" | grep -cxF "$f" || true)"
  if [[ "$count" -ne 1 ]]; then
    echo "architecture_files_test: kernel/src/$f is named $count times in docs/architecture.md's file tables (once wanted)"
    fail=1
  fi
done
while read -r f; do
  [[ -z "$f" ]] && continue
  if [[ ! -f "$root/kernel/src/$f" ]]; then
    echo "architecture_files_test: docs/architecture.md names kernel/src/$f, which does not exist"
    fail=1
  fi
done <<< "$listed"
if [[ $fail -ne 0 ]]; then exit 1; fi
echo "architecture_files_test: every one of $(printf '%s\n' "$listed" | wc -l) files of kernel/src named once"
