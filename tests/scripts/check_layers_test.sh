#!/usr/bin/env bash
# scripts/check-layers.sh catches what it is for: on a copy of kernel/ (which passes), each
# planted include that points up makes it exit 1 naming the file, the line and the include.
# The copy lives in a temporary folder of its own, so that parallel runs do not meet.
set -euo pipefail

source_dir="$(cd "$(dirname "$0")/../.." && pwd)"
check="$source_dir/scripts/check-layers.sh"
work="$(mktemp -d "${TMPDIR:-/tmp}/s2sim-check-layers.XXXXXX")"
trap 'rm -rf "$work"' EXIT
tree="$work/tree"
mkdir -p "$tree/kernel"
cp -r "$source_dir/kernel/src" "$source_dir/kernel/include" "$tree/kernel/"

if ! "$check" --root "$tree" > "$work/out.txt" 2>&1; then
  echo "FAIL: the unchanged copy of kernel/ does not pass:"
  cat "$work/out.txt"
  exit 1
fi

failures=0
# plant FILE INCLUDE EXPECTED: FILE (under the copy) gets INCLUDE as its second line; the check
# must exit 1 and print EXPECTED; the file is removed after.
plant() {
  local file="$1" include="$2" expected="$3" status=0
  mkdir -p "$(dirname "$tree/$file")"
  printf '// planted\n%s\n' "$include" > "$tree/$file"
  "$check" --root "$tree" > "$work/out.txt" 2>&1 || status=$?
  if [ "$status" -ne 1 ] || ! grep -qF -- "$expected" "$work/out.txt"; then
    echo "FAIL: $file with $include: exit $status (want 1), output (want '$expected'):"
    cat "$work/out.txt"
    failures=$((failures + 1))
  else
    echo "ok: $file with $include: $(head -n 1 "$work/out.txt")"
  fi
  rm -f "$tree/$file"
}

plant kernel/src/model/planted.cpp '#include "sim/step.hpp"' \
  'kernel/src/model/planted.cpp:2: #include "sim/step.hpp": model (layer 3) may not include sim'
plant kernel/src/contact/planted.hpp '#include <sim/names.hpp>' \
  'kernel/src/contact/planted.hpp:2: #include <sim/names.hpp>: contact (layer 4) may not include sim'
plant kernel/src/common/planted.hpp '#include "scene/xml.hpp"' \
  'kernel/src/common/planted.hpp:2: #include "scene/xml.hpp": common (layer 0) may not include scene'
plant kernel/src/scene/planted.cpp '#include "../sim/step.hpp"' \
  "kernel/src/scene/planted.cpp:2: #include \"../sim/step.hpp\": '..' is no kernel/src folder"
plant kernel/src/physics/planted.cpp '#include "common/assert.hpp"' \
  'kernel/src/physics/planted.cpp:2: #include "common/assert.hpp": kernel/src/physics has no layer'
plant kernel/include/s2sim/kernel/planted.hpp '#include "model/multibody.hpp"' \
  'kernel/include/s2sim/kernel/planted.hpp:2: #include "model/multibody.hpp": kernel/include may include only'

# Removed again, the copy passes: each failure above was the planted file's.
if ! "$check" --root "$tree" > "$work/out.txt" 2>&1; then
  echo "FAIL: the copy does not pass once the planted files are gone:"
  cat "$work/out.txt"
  failures=$((failures + 1))
fi
if [ "$failures" -gt 0 ]; then
  echo "check_layers_test: $failures case(s) failed"
  exit 1
fi
echo "check_layers_test: every planted upward include was caught"
