#!/usr/bin/env bash
# Times two revisions side by side: builds each in a worktree of its own (s2sim-peers and the
# plugins the peers' scenes load), runs `s2sim-peers` on them in turn RUNS times, and compares
# every round (bench/peers/compare_rounds.py).
#
#   scripts/peers-before-after.sh BEFORE AFTER [RUNS] [OUT]
#
# BEFORE and AFTER are revisions (AFTER may be "." for the working tree's build/), RUNS the
# alternations (default 8, 5 rounds each), OUT the folder the rounds CSVs go to (default a new
# temporary folder). S2SIM_PEERS_ARGS replaces the scenes and engines timed (default: robots_1,
# robots_16, robots_64, pile, humanoid and arm_loop on one thread and on two). The worktrees
# stay in OUT, so that a second call with the same OUT builds nothing; `git worktree remove`
# removes them.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [[ $# -lt 2 ]]; then
  sed -n '2,14p' "$0" >&2
  exit 2
fi
runs="${3:-8}"
out="${4:-$(mktemp -d -t s2sim-before-after-XXXXXX)}"
mkdir -p "$out"
args=(${S2SIM_PEERS_ARGS:---scenes robots_1,robots_16,robots_64,pile,humanoid,arm_loop
      --engines s2sim,s2sim-par2 --rounds 5})
plugins=(drive_train fluids links sensors servo vehicles joint_effort)

# build REV: prints the worktree whose build/bin/s2sim-peers is REV's.
build() {
  local rev="$1" tree
  if [[ "$rev" == "." ]]; then
    tree="$root"
  else
    tree="$out/tree-$(git -C "$root" rev-parse --short "$rev")"
    [[ -d "$tree" ]] || git -C "$root" worktree add -f --detach "$tree" "$rev" >&2
  fi
  (cd "$tree" && cmake --preset release >&2)
  local targets=(bin/s2sim-peers)
  for p in "${plugins[@]}"; do
    if ninja -C "$tree/build" -t targets all | grep -q "^plugins/lib$p.so:"; then
      targets+=("plugins/lib$p.so")
    fi
  done
  ninja -C "$tree/build" -j"$(nproc)" "${targets[@]}" >&2
  echo "$tree"
}

before_tree="$(build "$1")"
after_tree="$(build "$2")"
for ((i = 1; i <= runs; i++)); do
  for side in before after; do
    tree="${side}_tree"
    (cd "${!tree}" && build/bin/s2sim-peers "${args[@]}" --rounds-csv "$out/$side-$i-rounds.csv" \
      > /dev/null)
  done
done
echo "rounds in $out (load average now: $(cut -d' ' -f1-3 /proc/loadavg))"
"$root/bench/peers/compare_rounds.py" "$out/before-*-rounds.csv" "$out/after-*-rounds.csv"
