#!/usr/bin/env bash
# Behaviour check: runs every case of scripts/behaviour-cases.txt with the runner (CSV of every
# signal at every physics step, and the JSON summary without timing) and compares the SHA-256 of
# both files with a reference.
#
#   scripts/check-behaviour.sh [--bin DIR]                 compare with tests/golden/behaviour.sha256
#   scripts/check-behaviour.sh [--bin DIR] --update        rewrite tests/golden/behaviour.sha256
#   scripts/check-behaviour.sh [--bin DIR] --against REV   build REV in a worktree and compare the
#                                                          files themselves (first differing line)
#   scripts/check-behaviour.sh [--bin DIR] --threads N     run every case with --threads N: the
#                                                          same hashes (results do not depend on it)
#   scripts/check-behaviour.sh [--bin DIR] --check-dynamics
#                                                          run every case with --check-dynamics:
#                                                          Simbody's accelerations compared with
#                                                          the small-tree dynamics' at every
#                                                          substep (a case fails beyond their
#                                                          agreement), and the same hashes
#
# A restructuring must leave the hashes unchanged; a deliberate change of physics updates them in
# the same commit, which then shows which cases it changed. DIR defaults to build/bin. Cases whose
# scene is missing (../shared absent) are skipped and said so.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="$root/build/bin"
mode=check
against=""
threads=""
check_dynamics=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --bin) bin="$(cd "$2" && pwd)"; shift 2 ;;
    --update) mode=update; shift ;;
    --against) mode=against; against="$2"; shift 2 ;;
    --threads) threads="--threads $2"; shift 2 ;;
    --check-dynamics) check_dynamics="--check-dynamics"; shift ;;
    *) echo "check-behaviour: unknown option '$1'" >&2; exit 2 ;;
  esac
done
golden="$root/tests/golden/behaviour.sha256"
if [[ -n "$threads" && "$(nproc)" -lt "${threads#--threads }" ]]; then
  echo "check-behaviour: skipped, $threads needs more than this machine's $(nproc) threads" >&2
  exit 0
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# run_cases BIN OUTDIR: one CSV and one JSON per case.
run_cases() {
  local runner="$1/s2sim-run" out="$2"
  mkdir -p "$out"
  while IFS='|' read -r name scene args; do
    name="$(echo "$name" | xargs)"
    [[ -z "$name" || "$name" == \#* ]] && continue
    scene="$(echo "$scene" | xargs)"
    if [[ ! -e "$root/$scene" ]]; then
      echo "skipped: $name ($scene not found)" >&2
      continue
    fi
    local check="$check_dynamics"
    # shellcheck disable=SC2086
    (cd "$root" && "$runner" "$scene" $args $threads $check --quiet --no-timing \
      --log "$out/$name.csv" --summary "$out/$name.json" 2> "$out/$name.err") ||
      { echo "check-behaviour: case $name failed (exit $?):" >&2; cat "$out/$name.err" >&2; exit 1; }
    cat "$out/$name.err" >&2
    if [[ -n "$check" ]]; then
      echo "  $name: $(grep '^dynamics check:' "$out/$name.err" || echo 'no dynamics check line')"
    fi
  done < "$root/scripts/behaviour-cases.txt"
}

hashes() {  # hashes DIR: "sha256  name" lines, sorted
  (cd "$1" && sha256sum -- *.csv *.json | sort -k2)
}

case "$mode" in
  update)
    run_cases "$bin" "$work/now"
    hashes "$work/now" > "$golden"
    echo "check-behaviour: wrote $(wc -l < "$golden") hashes to tests/golden/behaviour.sha256"
    ;;
  check)
    run_cases "$bin" "$work/now"
    hashes "$work/now" > "$work/now.sha256"
    # Compare only the cases that ran here (a missing ../shared skips the SimTwo projects).
    fail=0; count=0
    while read -r sum file; do
      expected="$(awk -v f="$file" '$2 == f {print $1}' "$golden")"
      count=$((count + 1))
      if [[ -z "$expected" ]]; then
        echo "check-behaviour: $file has no reference hash (run --update)"; fail=1
      elif [[ "$expected" != "$sum" ]]; then
        echo "check-behaviour: $file differs from its reference"; fail=1
      fi
    done < "$work/now.sha256"
    if [[ $fail -ne 0 ]]; then
      echo "check-behaviour: behaviour changed; if deliberate, run scripts/check-behaviour.sh --update"
      echo "$count checked, some failed"
      exit 1
    fi
    echo "check-behaviour: $count files identical to tests/golden/behaviour.sha256"
    ;;
  against)
    tree="$work/ref"
    git -C "$root" worktree add --detach "$tree" "$against" >/dev/null
    trap 'git -C "$root" worktree remove --force "$tree"; rm -rf "$work"' EXIT
    cmake -S "$tree" -B "$tree/build" -DCMAKE_BUILD_TYPE=Release -DS2SIM_BUILD_TESTS=OFF \
      -DS2SIM_BUILD_BENCH=OFF -G Ninja >/dev/null
    cmake --build "$tree/build" -j2 --target s2sim-run drive_train sensors servo >/dev/null
    run_cases "$tree/build/bin" "$work/ref-out"
    run_cases "$bin" "$work/now"
    fail=0
    for f in "$work/ref-out"/*; do
      name="$(basename "$f")"
      if ! cmp -s "$f" "$work/now/$name"; then
        fail=1
        line="$(cmp "$f" "$work/now/$name" | awk '{print $NF}')"
        echo "check-behaviour: $name differs from $against at line $line"
      fi
    done
    [[ $fail -eq 0 ]] && echo "check-behaviour: every file identical to $against"
    exit $fail
    ;;
esac
