# Sourced by the plot scripts (scripts/plot-*.sh BUILD_DIR): sets root (the source tree),
# build (the script's first argument, default root/build), run (its s2sim-run) and out
# (docs/images, made), after checking that gnuplot and the runner are there.
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
run="$build/bin/s2sim-run"
out="$root/docs/images"
command -v gnuplot >/dev/null || { echo "gnuplot missing: apt-get install gnuplot-nox" >&2; exit 1; }
[ -x "$run" ] || { echo "no runner at $run: build first" >&2; exit 1; }
mkdir -p "$out"
