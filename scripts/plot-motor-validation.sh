#!/usr/bin/env bash
# Validation plots of the DC motor model (docs/models/dc-motor.md): runs s2sim-run on
# scenes/motor_bench with --log and draws PNGs into docs/images/ with gnuplot (gnuplot-nox).
#
#   scripts/plot-motor-validation.sh [BUILD_DIR]      (default: build)
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/plot-setup.sh" "$@"
bench="$root/scenes/motor_bench"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
axis=robots/bench/axes/motor

# 1. Free-running speed against voltage, 1..9 V: the speed after 1.2 s (40 time constants).
: > "$tmp/speed.dat"
for u in 1 2 3 4 5 6 7 8 9; do
  "$run" "$bench" --quiet --no-timing --duration 1.2 --set "$axis/ref_voltage=$u" \
    --log "$tmp/u$u.csv" --log-period 1.2 --signals "$axis/speed"
  echo "$u $(tail -n 1 "$tmp/u$u.csv" | cut -d, -f2)" >> "$tmp/speed.dat"
done

# 2. Start-up at 9 V from rest: speed and current.
"$run" "$bench" --quiet --no-timing --duration 0.25 --set "$axis/ref_voltage=9" \
  --log "$tmp/start.csv" --signals "$axis/speed" "$axis/current"

# 3. Stall (a Coulomb brake of 100 N·m holds the axis): 9 V step, current against the exact
#    U/Ra (1 − exp(−t Ra/La)), at 1 ms and at 5 ms.
"$run" "$bench" --quiet --no-timing --define fc=100 --duration 0.01 \
  --set "$axis/ref_voltage=9" --log "$tmp/stall1.csv" --signals "$axis/current"
"$run" "$bench" --quiet --no-timing --define fc=100 --duration 0.01 --physics-step 0.005 \
  --set "$axis/ref_voltage=9" --log "$tmp/stall5.csv" --signals "$axis/current"

# 4. pidspeed (the bench's gains) to 10 rad/s from rest.
"$run" "$bench" --quiet --no-timing --duration 1 --set "$axis/controller_active=1" \
  --set "$axis/ref_speed=10" --log "$tmp/pid.csv" --signals "$axis/speed" "$axis/voltage"

gnuplot <<GP
set terminal pngcairo size 800,500 font ",11"
set datafile separator ","
set grid
set key left top

set output "$out/motor-speed-vs-voltage.png"
set title "NXT motor, free-running speed vs voltage (motor\\\\_bench)"
set xlabel "terminal voltage Ua (V)"; set ylabel "speed (rad/s)"
set datafile separator " "
plot 1.9211*x - 0.0106 title "paper (3.11): 1.9211 Ua - 0.0106" lw 2, \
     "$tmp/speed.dat" using 1:2 with points pt 7 ps 1.5 title "S2Sim"
set datafile separator ","

set output "$out/motor-startup-9v.png"
set title "NXT motor + 1e-3 kg m^2 flywheel, 9 V step from rest (1 ms step)"
set xlabel "time (s)"; set ylabel "speed (rad/s)"; set y2label "current (A)"
set ytics nomirror; set y2tics
plot "$tmp/start.csv" using 1:2 every ::1 with lines lw 2 title "speed", \
     "$tmp/start.csv" using 1:3 every ::1 axes x1y2 with lines lw 2 title "current"
unset y2label; unset y2tics; set ytics mirror

set output "$out/motor-stall-current.png"
set title "Stall current after a 9 V step: exact exponential update"
set xlabel "time (ms)"; set ylabel "current (A)"; set key right bottom
set samples 400
plot [0:10] 9/7.6*(1-exp(-x/1000*7.6/4.88e-3)) title "U/Ra (1 - exp(-t Ra/La))" lw 2, \
     "$tmp/stall1.csv" using (\$1*1000):2 every ::1 with points pt 7 title "S2Sim, 1 ms step", \
     "$tmp/stall5.csv" using (\$1*1000):2 every ::1 with points pt 5 ps 1.5 title "S2Sim, 5 ms step"

set output "$out/motor-pidspeed.png"
set title "pidspeed (10 ms, Kp 1, Ki 10, Kf 0.52) to 10 rad/s"
set xrange [0:0.4]
set xlabel "time (s)"; set ylabel "speed (rad/s)"; set y2label "voltage (V)"; set key right bottom
set ytics nomirror; set y2tics
plot "$tmp/pid.csv" using 1:2 every ::1 with lines lw 2 title "speed", \
     10*1.02 with lines dt 2 lc rgb "gray" title "±2 %", 10*0.98 with lines dt 2 lc rgb "gray" notitle, \
     "$tmp/pid.csv" using 1:3 every ::1 axes x1y2 with lines lw 2 title "voltage"
GP
echo "plots written to $out"
ls -1 "$out"/motor-*.png
