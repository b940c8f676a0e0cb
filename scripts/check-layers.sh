#!/usr/bin/env bash
# The kernel's layers point only down (docs/architecture.md, "Layers"). Reads every #include of
# kernel/src, kernel/include and kernel/library and fails on one that points up:
# - kernel/src/<folder>/...: a file may include its own folder and the folders below it
#   (common < scene < collision < model < contact < plugin < sim), by "folder/file" or
#   <folder/file>; a folder missing from that list fails too, so that a new one gets a place;
# - kernel/include (the public API) and kernel/library (built against it alone): only
#   <s2sim/...> (the SDK and the public API) and system headers, nothing of kernel/src.
# Usage: scripts/check-layers.sh [--root DIR]   (DIR: the tree to check, this one by default)
# Exit 0 when every include points down, 1 listing each offending include, 2 on bad usage.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
while [ $# -gt 0 ]; do
  case "$1" in
    --root)
      [ $# -ge 2 ] || { echo "check-layers: --root needs a folder" >&2; exit 2; }
      root="$2"
      shift 2
      ;;
    -h | --help)
      sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'
      exit 0
      ;;
    *)
      echo "check-layers: unknown argument '$1'" >&2
      exit 2
      ;;
  esac
done
[ -d "$root/kernel/src" ] || { echo "check-layers: no kernel/src under '$root'" >&2; exit 2; }
root="$(cd "$root" && pwd)"

# Bottom first: a folder's rank is its place in this list.
layers=(common scene collision model contact plugin sim)
order="${layers[*]}"
order="${order// / < }"
declare -A rank
for i in "${!layers[@]}"; do
  rank[${layers[$i]}]=$i
done

include_re='^[[:space:]]*#[[:space:]]*include[[:space:]]*(["<])([^">]+)[">]'
failures=0

fail() {  # file line include rule
  echo "$1:$2: #include $3: $4"
  failures=$((failures + 1))
}

# Every include of the files under $1, as "path<TAB>line<TAB>text", sorted for a stable report.
includes_under() {
  [ -d "$1" ] || return 0
  find "$1" -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.inl' \) -print0 |
    sort -z | xargs -0 -r grep -n -H -E "$include_re" /dev/null |
    sed -E 's/^([^:]*):([0-9]+):/\1\t\2\t/' || true
}

while IFS=$'\t' read -r path line text; do
  [[ "$text" =~ $include_re ]] || continue
  quote="${BASH_REMATCH[1]}"
  target="${BASH_REMATCH[2]}"
  rel="${path#"$root"/}"
  folder="${rel#kernel/src/}"
  folder="${folder%%/*}"
  shown="$quote$target$([ "$quote" = '"' ] && echo '"' || echo '>')"
  if [ -z "${rank[$folder]+x}" ]; then
    fail "$rel" "$line" "$shown" "kernel/src/$folder has no layer (add it to scripts/check-layers.sh and docs/architecture.md)"
    continue
  fi
  # "file.hpp" is resolved beside the includer, in its own layer; <cmath> is the system's.
  [[ "$target" == */* ]] || continue
  to="${target%%/*}"
  if [ -z "${rank[$to]+x}" ]; then
    # Other libraries' headers (<s2sim/...>, <fcl/...>) are no layer; a quoted include
    # ("../x.hpp", "foo/x.hpp") must name a kernel folder, so that it is checked.
    [ "$quote" = '<' ] ||
      fail "$rel" "$line" "$shown" "'$to' is no kernel/src folder: name one of $order"
    continue
  fi
  if [ "${rank[$to]}" -gt "${rank[$folder]}" ]; then
    fail "$rel" "$line" "$shown" "$folder (layer ${rank[$folder]}) may not include $to (layer ${rank[$to]}): includes point down"
  fi
done < <(includes_under "$root/kernel/src")

for public in kernel/include kernel/library; do
  while IFS=$'\t' read -r path line text; do
    [[ "$text" =~ $include_re ]] || continue
    quote="${BASH_REMATCH[1]}"
    target="${BASH_REMATCH[2]}"
    rel="${path#"$root"/}"
    to="${target%%/*}"
    if [ "$quote" = '"' ]; then
      fail "$rel" "$line" "\"$target\"" "$public may include only <s2sim/...> and system headers, not kernel/src"
    elif [[ "$target" == */* ]] && [ -n "${rank[$to]+x}" ]; then
      fail "$rel" "$line" "<$target>" "$public may include only <s2sim/...> and system headers, not kernel/src"
    fi
  done < <(includes_under "$root/$public")
done

if [ "$failures" -gt 0 ]; then
  echo "check-layers: $failures include(s) point up (layers, bottom first: $order)" >&2
  exit 1
fi
echo "check-layers: every include of kernel/ points down (layers, bottom first: $order)"
