#!/usr/bin/env bash
# Step cost against the number of robots (it once grew with the square, then the cube, of the
# count; it should stay linear). N copies of scenes/nxt, 0.3 m apart on a grid, standing (no voltage), 2 s at
# 1 ms; prints the wall time per step and per robot-step from s2sim-run's summary.
#   bench/robot_count_bench.sh [BUILD_DIR] [COUNTS...]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
shift || true
counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(1 4 16 64 200)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$here/scenes/nxt/nxt.xml" "$work/"
printf '| robots | µs per step | µs per robot-step |\n|---:|---:|---:|\n'
for n in "${counts[@]}"; do
  side=$(awk -v n="$n" 'BEGIN { s = int(sqrt(n)); if (s * s < n) s++; print s }')
  {
    echo "<scene>"
    for ((i = 0; i < n; i++)); do
      echo "<robot><ID name='r$i'/><pos x='$(awk -v i=$i -v s=$side 'BEGIN{print (i%s)*0.3}')' y='$(awk -v i=$i -v s=$side 'BEGIN{print int(i/s)*0.3}')' z='0'/><body file='nxt.xml'/></robot>"
    done
    echo "</scene>"
  } >"$work/scene.xml"
  "$build/bin/s2sim-run" "$work/scene.xml" --quiet --duration 2 --summary "$work/s.json"
  awk -v n="$n" -F'[:,]' '/"wall_time"/ { w = $2 } /"steps"/ { s = $2 }
    END { printf "| %d | %.1f | %.2f |\n", n, 1e6 * w / s, 1e6 * w / s / n }' "$work/s.json"
done
