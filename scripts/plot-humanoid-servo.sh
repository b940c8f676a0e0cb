#!/usr/bin/env bash
# The humanoid's servo step response (docs/tutorials/humanoid-walk.md), as the SimTwo paper's
# Figure 20: scenes/humanoid standing without its script, the right elbow's goal stepped from
# 0 to 60° at t = 0; the goal, the servo's speed-limited setpoint and the measured angle
# against time, into docs/images/humanoid-servo-step.png with gnuplot (gnuplot-nox).
#
#   scripts/plot-humanoid-servo.sh [BUILD_DIR]      (default: build)
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/plot-setup.sh" "$@"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

axis=robots/humanoid/axes/elbow_r
"$run" "$root/scenes/humanoid" --quiet --no-timing --no-script --duration 0.4 \
  --set "$axis/ref_pos=1.0471975511965976" --log "$tmp/step.csv" \
  --signals "$axis/servo_setpoint" "$axis/pos" "$axis/servo_torque"
gnuplot <<GP
set terminal pngcairo size 800,500 font ",11"
set output "$out/humanoid-servo-step.png"
set datafile separator ","
set key bottom right
set grid
set xlabel "time (s)"
set ylabel "elbow angle (deg)"
set y2label "servo torque (N m)"
set ytics nomirror
set y2tics
set yrange [-5:70]
set xrange [0:0.4]
set y2range [-0.5:1.6]
d = 180/pi
set title "AX-12 servo step response: the humanoid's right elbow, 0 to 60 deg (1.5 N m, 6.18 rad/s)"
plot (x >= 0 ? 60 : 0) with lines lw 2 dt 2 lc rgb "black" title "commanded (goal)", \
     "$tmp/step.csv" every ::1 using 1:(\$2*d) with lines lw 2 lc rgb "#1f77b4" title "servo setpoint (speed-limited)", \
     "$tmp/step.csv" every ::1 using 1:(\$3*d) with lines lw 2 lc rgb "#d62728" title "measured angle", \
     "$tmp/step.csv" every ::1 using 1:4 axes x1y2 with lines lw 1 lc rgb "#2ca02c" title "servo torque (right axis)"
GP
echo "wrote $out/humanoid-servo-step.png"
