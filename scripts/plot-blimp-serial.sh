#!/usr/bin/env bash
# The blimp flown over the serial link (docs/tutorials/blimp-serial.md): builds
# examples/blimp_serial's C pilot, flies scenes/blimp_serial with it in lock-step and draws
# docs/images/blimp-serial-path.png with gnuplot (gnuplot-nox): the gondola's path from above
# against the waypoints, and its altitude against each waypoint's.
#
#   scripts/plot-blimp-serial.sh [BUILD_DIR]      (default: build)
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/plot-setup.sh" "$@"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/s2sim-plot-blimp-serial-$$-XXXXXX")"
runner=""
trap '[ -n "$runner" ] && kill "$runner" 2>/dev/null; rm -rf "$tmp"' EXIT

cmake -S "$root/examples/blimp_serial" -B "$tmp/pilot" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$tmp/pilot" > /dev/null

# The scene with its device link in this folder, so that no other run's link is taken.
mkdir "$tmp/scene"
sed "s|link='/tmp/ttyS2SIM_blimp'|link='$tmp/tty'|" "$root/scenes/blimp_serial/scene.xml" \
  > "$tmp/scene/scene.xml"
cp "$root/scenes/blimp_serial/blimp.xml" "$tmp/scene/"
"$run" "$tmp/scene" --quiet --no-timing --duration 55 --define serial_wait_s=10 --log "$tmp/flight.csv" --log-period 0.1 \
  --signals robots/blimp/solids/gondola/x robots/blimp/solids/gondola/y \
  robots/blimp/solids/gondola/z 2> "$tmp/run.err" &
runner=$!
for _ in $(seq 300); do [ -L "$tmp/tty" ] && break; sleep 0.1; done
"$tmp/pilot/blimp_serial_pilot" --waypoints "$root/scenes/blimp_serial/waypoints.txt" "$tmp/tty" \
  > "$tmp/pilot.out"
wait "$runner" || { cat "$tmp/run.err" >&2; exit 1; }
runner=""
cat "$tmp/pilot.out"

# The waypoints as CSV (the log's separator), and the time each was reached.
grep -v '^#' "$root/scenes/blimp_serial/waypoints.txt" | awk 'NF == 3 { print $1 "," $2 "," $3 }' \
  > "$tmp/waypoints.dat"
sed -n 's/^waypoint \([0-9]*\) (\([^ ]*\) \([^ ]*\) \([^ ]*\)) reached at \([0-9.]*\) s$/\5,\4/p' \
  "$tmp/pilot.out" > "$tmp/reached.dat"
gnuplot <<GP
set terminal pngcairo size 1100,520 font ",11"
set output "$out/blimp-serial-path.png"
set datafile separator ","
set multiplot layout 1,2 title "scenes/blimp_serial: the C pilot flies the blimp over the serial link (lock-step)" noenhanced
set grid
set key outside bottom center horizontal
set size ratio -1
set xlabel "x (m)"
set ylabel "y (m)"
set title "gondola path from above; waypoints (x, y, z in m)" noenhanced
set xrange [-0.8:3.8]
set yrange [-0.8:3.8]
plot "$tmp/flight.csv" every ::1 using 2:3 with lines lw 2 title "path", \
     "$tmp/waypoints.dat" using 1:2 with points pt 6 ps 3 lw 2 title "waypoints", \
     "$tmp/waypoints.dat" using (\$1+0.15):(\$2+0.15):(sprintf("(%g, %g, %g)", \$1, \$2, \$3)) \
       with labels left notitle
set size noratio
set autoscale
set xlabel "time (s)"
set ylabel "z (m)"
set yrange [0.8:2.8]
set title "gondola altitude; circles: a waypoint reached (within 0.2 m)" noenhanced
plot "$tmp/flight.csv" every ::1 using 1:4 with lines lw 2 title "z", \
     "$tmp/reached.dat" using 1:2 with points pt 6 ps 2 lw 2 title "waypoint reached"
unset multiplot
GP
echo "wrote $out/blimp-serial-path.png"
