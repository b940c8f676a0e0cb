#!/usr/bin/env bash
# s2sim-view frame-rate benchmark (docs/viewer.md): renders a scene at 1280x720 under Xvfb
# (Mesa llvmpipe, no GPU) with the simulation playing at real time and the Run window open,
# without frame cap or vsync, and prints the steady-state frames per second.
#
#   bench/viewer_fps_bench.sh [BUILD_DIR] [SCENE] [FRAMES]
#
# Measure on an otherwise idle machine: llvmpipe uses every core.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
scene="${2:-$here/../scenes/default}"
frames="${3:-600}"
command -v xvfb-run >/dev/null || { echo "viewer_fps_bench: xvfb-run is missing (apt-get install xvfb)" >&2; exit 1; }
xvfb-run -a -s "-screen 0 1280x720x24" "$build/bin/s2sim-view" "$scene" --size 1280x720 \
  --frames "$frames" --no-frame-cap --report-fps
