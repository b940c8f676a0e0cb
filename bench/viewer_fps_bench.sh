#!/usr/bin/env bash
# s2sim-view frame-rate benchmark (docs/viewer.md): renders scenes at 1280x720 under Xvfb
# (Mesa llvmpipe, no GPU) with the simulation playing at real time and the Run window open,
# without frame cap or vsync, and prints the steady-state frames per second of each run.
#
#   bench/viewer_fps_bench.sh [BUILD_DIR] [SCENE|all] [FRAMES] [REPEATS]
#
# SCENE "all" (the default) measures every scene of scenes/ and every shared SimTwo project
# (../shared/simtwo-scenes, when the checkout sits next to it), REPEATS times each, and ends
# with a table of the lowest, median and highest frame rate per scene. llvmpipe uses every
# core: other work on the machine lowers the figures, hence the repeats.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
which="${2:-all}"
frames="${3:-300}"
repeats="${4:-3}"
command -v xvfb-run >/dev/null || { echo "viewer_fps_bench: xvfb-run is missing (apt-get install xvfb)" >&2; exit 1; }

scenes=()
if [ "$which" = all ]; then
  for s in "$here"/../scenes/*/ "$here"/../../shared/simtwo-scenes/*/; do
    [ -f "$s/scene.xml" ] && scenes+=("$(cd "$s" && pwd)")
  done
else
  scenes=("$which")
fi

summary=""
for scene in "${scenes[@]}"; do
  rates=()
  # A lock-step remote link (cartpole_remote, firefighting_omni) waits for a client that the
  # benchmark does not start: a free port, and 10 ms of waiting before it runs on without one
  # (not its 10 s).
  extra=()
  case "$(basename "$scene")" in cartpole_remote | firefighting_omni)
    extra=(--define remote_port=0 --define remote_wait_s=0.01) ;;
  esac
  for ((i = 1; i <= repeats; i++)); do
    line=$(xvfb-run -a -s "-screen 0 1280x720x24" "$build/bin/s2sim-view" "$scene" --size 1280x720 \
      --frames "$frames" --no-frame-cap --report-fps "${extra[@]}" | grep '^frames' || true)
    echo "$(basename "$(dirname "$scene")")/$(basename "$scene") run $i: ${line:-failed}"
    rate=$(sed -n 's/.*: \([0-9.]*\) frames per second.*/\1/p' <<<"$line")
    rates+=("${rate:-0}")
  done
  sorted=$(printf '%s\n' "${rates[@]}" | sort -g | tr '\n' ' ')
  read -r -a s <<<"$sorted"
  summary+=$(printf '%-26s min %6s  median %6s  max %6s fps\n' "$(basename "$(dirname "$scene")")/$(basename "$scene")" \
    "${s[0]}" "${s[$(((${#s[@]} - 1) / 2))]}" "${s[${#s[@]} - 1]}")$'\n'
done
echo "--- $(date -u +%H:%M) UTC, load average $(cut -d' ' -f1-3 /proc/loadavg), $frames frames x $repeats"
printf '%s' "$summary"
