#!/usr/bin/env bash
# Plots of the fluid models (docs/models/fluids.md): runs s2sim-run with --log and draws PNGs
# into docs/images/ with gnuplot (gnuplot-nox):
#   fluids-terminal-velocity.png  a sphere falling in air against v_t·tanh(g·t/v_t)
#   fluids-blimp-path.png         scenes/blimp's path seen from above, with its waypoints
#
#   scripts/plot-fluids.sh [BUILD_DIR]      (default: build)
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/plot-setup.sh" "$@"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# 1. The drag test's sphere (0.05 kg, r = 0.1 m, Cd 0.47, rho 1.225) falling for 6 s.
"$run" "$root/tests/plugins/fluids/fixtures/sphere_air" --quiet --no-timing --duration 6 \
  --log "$tmp/fall.csv" --log-period 0.02 --signals robots/ball/solids/ball/vz
gnuplot <<GP
set terminal pngcairo size 800,500 font ",11"
set output "$out/fluids-terminal-velocity.png"
set datafile separator ","
set key bottom right
set grid
set xlabel "time (s)"
set ylabel "falling speed (m/s)"
m = 0.05; r = 0.1; cd = 0.47; rho = 1.225; g = 9.81
vt = sqrt(2*m*g/(rho*cd*pi*r*r))
set title sprintf("Sphere falling in air: terminal velocity %.3f m/s", vt)
plot "$tmp/fall.csv" every ::1 using 1:(-\$2) with points pt 7 ps 0.5 title "S2Sim (drag plugin)", \
     vt*tanh(g*x/vt) with lines lw 2 title "analytic v_t tanh(g t / v_t)", \
     vt with lines dt 2 title "v_t = sqrt(2mg / (rho Cd A))"
GP

# 2. The blimp's flight through its waypoints.
"$run" "$root/scenes/blimp" --quiet --no-timing --duration 90 --log "$tmp/blimp.csv" \
  --log-period 0.2 --signals robots/blimp/solids/gondola/x robots/blimp/solids/gondola/y \
  robots/blimp/solids/gondola/z
printf '3,0,2\n3,3,2.5\n0,3,2\n0,0,1.5\n' > "$tmp/waypoints.dat"  # the CSV separator
gnuplot <<GP
set terminal pngcairo size 700,650 font ",11"
set output "$out/fluids-blimp-path.png"
set datafile separator ","
set size ratio -1
set grid
set key outside bottom center horizontal
set xlabel "x (m)"
set ylabel "y (m)"
set title "scenes/blimp: gondola path from above, waypoints (x, y, z in m)"
set xrange [-0.8:3.8]
set yrange [-0.8:3.8]
plot "$tmp/blimp.csv" every ::1 using 2:3 with lines lw 2 title "path", \
     "$tmp/waypoints.dat" using 1:2 with points pt 6 ps 3 lw 2 title "waypoints", \
     "$tmp/waypoints.dat" using (\$1+0.15):(\$2+0.15):(sprintf("(%g, %g, %g)", \$1, \$2, \$3)) \
       with labels left notitle
GP
echo "wrote $out/fluids-terminal-velocity.png $out/fluids-blimp-path.png"
