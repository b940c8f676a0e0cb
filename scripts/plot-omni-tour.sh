#!/usr/bin/env bash
# Plots of the omni robot's tour of the Fire-Fighting arena (docs/tutorials/omni-localisation.md):
# runs scenes/firefighting_omni with python/examples/omni_tour.py in lock-step and draws PNGs
# into docs/images/ with gnuplot (gnuplot-nox):
#   omni-tour-paths.png  the arena from above: the true path, the particle filter's estimate,
#                        the odometry alone, the rooms' goals
#   omni-tour-error.png  the estimate's position error over the tour, with the filter's own
#                        2-sigma spread, against the odometry's error
#
#   scripts/plot-omni-tour.sh [BUILD_DIR]      (default: build)
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/plot-setup.sh" "$@"
python=/usr/bin/python3  # Debian's, with NumPy
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"; [ -n "${sim:-}" ] && kill "$sim" 2>/dev/null || true' EXIT

# The run: the simulation picks a port and says it on stderr; the client takes it from there.
"$run" "$root/scenes/firefighting_omni" --quiet --no-timing --duration 42 \
  --define remote_port=0 2> "$tmp/sim.err" &
sim=$!
for _ in $(seq 100); do
  port="$(sed -n 's/.*udp 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$tmp/sim.err")"
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || { cat "$tmp/sim.err" >&2; exit 1; }
PYTHONPATH="$build/python" "$python" "$root/python/examples/omni_tour.py" --port "$port" \
  --seed 7 --log "$tmp/tour.csv" | tee "$tmp/tour.out"
wait "$sim"
sim=

# The walls as gnuplot rectangles, from the scene's own file.
"$python" - "$root/scenes/firefighting_omni/arena.xml" > "$tmp/walls.gp" <<'PY'
import sys, xml.etree.ElementTree as ET
for k, box in enumerate(ET.parse(sys.argv[1]).getroot().iter("cuboid")):
    s, p = box.find("size"), box.find("pos")
    x, y, hx, hy = float(p.get("x")), float(p.get("y")), float(s.get("x")) / 2, float(s.get("y")) / 2
    print("set object %d rect from %g,%g to %g,%g fc rgb '#606060' fs solid noborder"
          % (k + 1, x - hx, y - hy, x + hx, y + hy))
PY
PYTHONPATH="$build/python" "$python" - "$root/python/examples" > "$tmp/goals.dat" <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
from omni_tour import TOUR
for x, y, room in TOUR:
    if room:
        print("%g,%g,%s" % (x, y, room))
PY
rms="$(sed -n 's/.*error \([0-9.]*\) m RMS.*/\1/p' "$tmp/tour.out")"

gnuplot <<GP
set terminal pngcairo size 760,720 font ",11" noenhanced
set output "$out/omni-tour-paths.png"
set datafile separator ","
set size ratio -1
set key outside bottom center horizontal
set xlabel "x (m)"
set ylabel "y (m)"
set xrange [-0.1:2.54]
set yrange [-0.1:2.54]
set title sprintf("scenes/firefighting_omni: the tour from above (estimate %.1f mm RMS)", $rms * 1000)
load "$tmp/walls.gp"
plot "$tmp/tour.csv" every ::1 using 8:9 with lines lw 4 lc rgb "#a0c8f0" title "true", \
     "$tmp/tour.csv" every ::1 using 2:3 with lines lw 1.5 lc rgb "#c00000" title "particle filter", \
     "$tmp/tour.csv" every ::1 using 11:12 with lines lw 1 dt 2 lc rgb "#208020" title "odometry alone", \
     "$tmp/goals.dat" using 1:2 with points pt 7 ps 1.5 lc rgb "black" title "room goals", \
     "$tmp/goals.dat" using (\$1+0.06):(\$2+0.06):3 with labels left notitle
GP

gnuplot <<GP
set terminal pngcairo size 800,450 font ",11"
set output "$out/omni-tour-error.png"
set datafile separator ","
set key top left
set grid
set xlabel "time (s)"
set ylabel "position error (mm)"
set title "Position error over the tour, IR noise on"
plot "$tmp/tour.csv" every ::1 using 1:(\$15 > 0 ? 2000*sqrt(\$5**2 + \$6**2) : 1/0) \
       with filledcurves y1=0 fc rgb "#f0d0d0" title "filter's 2 sigma (particle spread)", \
     "$tmp/tour.csv" every ::1 using 1:(\$15 > 0 ? 1000*sqrt((\$2-\$8)**2 + (\$3-\$9)**2) : 1/0) \
       with lines lw 1.5 lc rgb "#c00000" title "particle filter", \
     "$tmp/tour.csv" every ::1 using 1:(\$15 > 0 ? 1000*sqrt((\$11-\$8)**2 + (\$12-\$9)**2) : 1/0) \
       with lines lw 1 dt 2 lc rgb "#208020" title "odometry alone"
GP
echo "wrote $out/omni-tour-paths.png and $out/omni-tour-error.png"
