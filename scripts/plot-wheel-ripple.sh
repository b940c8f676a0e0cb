#!/usr/bin/env bash
# The step-to-step wheel-speed ripple of the NXT-class two-wheeler
# (tests/plugins/drive_train/fixtures/two_wheeler) driven straight at 6 V, before and after a
# change. Runs the fixture for 1 s with each runner binary (1 ms step, 1 substep, every step
# logged) and draws the right wheel's speed per physics step from 0.4 s to 0.5 s, one panel
# per runner, with gnuplot (gnuplot-nox), into one PNG.
#
#   scripts/plot-wheel-ripple.sh RUNNER_BEFORE RUNNER_AFTER [OUT_PNG] [NAME=VALUE ...]
#
# OUT_PNG defaults to docs/images/wheel-speed-ripple.png. NAME=VALUE pairs are passed to both
# runs as --define, e.g. li=0 (the motor's inductance neglected) or wheel_mass=0.02 (the NXT's
# own tyre): the fixture's variants that ring when the stiff axis forces act explicitly,
# through the previous step's speed.
#   scripts/plot-wheel-ripple.sh /work/main/build/bin/s2sim-run build/bin/s2sim-run '' li=0
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
usage() { echo "usage: $0 RUNNER_BEFORE RUNNER_AFTER [OUT_PNG] [NAME=VALUE ...]" >&2; exit 4; }
[ $# -ge 2 ] || usage
before="$1"
after="$2"
out="${3:-}"
[ -n "$out" ] || out="$root/docs/images/wheel-speed-ripple.png"
shift $(($# < 3 ? $# : 3))
defines=()
for d in "$@"; do
  [[ "$d" == *=* ]] || usage
  defines+=(--define "$d")
done
command -v gnuplot >/dev/null || { echo "gnuplot missing: apt-get install gnuplot-nox" >&2; exit 1; }
for r in "$before" "$after"; do
  [ -x "$r" ] || { echo "no runner at $r: build first" >&2; exit 1; }
done
scene="$root/tests/plugins/drive_train/fixtures/two_wheeler"
axes=robots/wheeler/axes
mkdir -p "$(dirname "$out")"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# 6 V, no controller: the right wheel (-90°) positive and the left negative drive it forward.
run() {  # RUNNER CSV
  "$1" "$scene" --quiet --no-timing --duration 1 --physics-step 0.001 --substeps 1 \
    ${defines[@]+"${defines[@]}"} \
    --set "$axes/right/ref_voltage=6" --set "$axes/left/ref_voltage=-6" \
    --log "$2" --signals "$axes/right/speed" "$axes/left/speed"
}
run "$before" "$tmp/before.csv"
run "$after" "$tmp/after.csv"

# Ripple over the plotted window: max |w_k - w_(k-1)| / |mean w|, for the titles.
ripple() {
  awk -F, 'NR > 1 && $1 >= 0.4 - 1e-9 && $1 <= 0.5 + 1e-9 {
             if (n++) { d = $2 - p; if (d < 0) d = -d; if (d > m) m = d }
             s += $2; p = $2 }
           END { mean = s / n; if (mean < 0) mean = -mean;
                 printf "mean %.3f rad/s, step-to-step ripple %.3g %%", s / n, 100 * m / mean }' "$1"
}
label="${*:-li 4.88 mH, the fixture's default}"
gnuplot <<GP
set terminal pngcairo size 900,700 font ",11"
set output "$out"
set datafile separator ","
set grid
set xrange [0.4:0.5]
set xlabel "time (s)"; set ylabel "right wheel speed (rad/s)"
set multiplot layout 2,1 title "Two-wheeler (NXT-class motor, 50 g tyres) at 6 V, 1 ms step, 1 substep: wheel speed per step ($label)"
set title "before: $(ripple "$tmp/before.csv")\n$before"
plot "$tmp/before.csv" using 1:2 with linespoints pt 7 ps 0.5 lc rgb "#c0392b" title "before"
set title "after: $(ripple "$tmp/after.csv")\n$after"
plot "$tmp/after.csv" using 1:2 with linespoints pt 7 ps 0.5 lc rgb "#2471a3" title "after"
unset multiplot
GP
echo "$out"
