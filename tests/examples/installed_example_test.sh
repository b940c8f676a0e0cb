#!/bin/bash
# Builds examples/ against an installed S2Sim and runs it (tests/examples/CMakeLists.txt).
#   installed_example_test.sh install|deb BUILD_DIR SOURCE_DIR CMAKE GENERATOR CXX VERSION
set -euo pipefail
mode=$1 build=$2 src=$3 cmake=$4 generator=$5 cxx=$6 version=$7
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset S2SIM_PLUGIN_PATH
fail() { echo "FAIL: $*" >&2; exit 1; }
step() { echo "== $* ($(date +%s.%N | cut -c1-14))"; }

case $mode in
  install)
    step "cmake --install to a temporary prefix"
    "$cmake" --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log"
    prefix=$tmp/prefix ;;
  deb)
    step "cpack -G DEB, then dpkg-deb -x into a temporary folder"
    (cd "$tmp" && "$(dirname "$cmake")/cpack" -G DEB --config "$build/CPackConfig.cmake" \
       -B "$tmp/package" > "$tmp/cpack.log") || { cat "$tmp/cpack.log"; fail "cpack"; }
    deb=$(ls "$tmp"/package/s2sim_*.deb)
    echo "package: $(basename "$deb"), $(du -k "$deb" | cut -f1) kB"
    dpkg-deb -f "$deb" Package Version Depends
    [ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || fail "package version is not $version"
    dpkg-deb -x "$deb" "$tmp/root"
    prefix=$tmp/root/usr ;;
  *) fail "unknown mode $mode" ;;
esac

step "the installed files"
for f in bin/s2sim-run bin/s2sim-view lib/libs2sim.so lib/s2sim/plugins/libdrive_train.so \
         lib/s2sim/plugins/libsensors.so include/s2sim/sdk.hpp include/s2sim/kernel/simulation.hpp \
         lib/cmake/S2Sim/S2SimConfig.cmake lib/cmake/S2Sim/S2SimConfigVersion.cmake \
         lib/cmake/S2Sim/S2SimTargets.cmake lib/cmake/S2Sim/S2SimPlugin.cmake lib/pkgconfig/s2sim.pc; do
  [ -e "$prefix/$f" ] || fail "$f is not installed"
done
if grep -rE "^\s*#\s*include\s*[<\"](Simbody|SimTK|simbody|fcl/|Eigen|boost/)" "$prefix/include"; then
  fail "a public header includes Simbody, FCL, Eigen or Boost"
fi
if grep -rl "$build" "$prefix/lib/cmake" "$prefix/lib/pkgconfig"; then
  fail "the CMake package or pkg-config file names the build tree"
fi
got=$("$prefix/bin/s2sim-run" --version)
echo "$got"
[[ $got == "s2sim-run $version "* ]] || fail "s2sim-run --version is not $version"
pc() { PKG_CONFIG_PATH=$prefix/lib/pkgconfig pkg-config "$@"; }
[ "$(pc --modversion s2sim)" = "$version" ] || fail "pkg-config version"
[ -d "$(pc --variable=plugindir s2sim)" ] || fail "pkg-config plugindir"

step "examples/ configured and built against it with -Wall -Wextra -Wpedantic -Werror"
"$cmake" -S "$src/examples" -B "$tmp/examples" -G "$generator" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_CXX_FLAGS="-Wall -Wextra -Wpedantic -Werror" > "$tmp/configure.log" ||
  { cat "$tmp/configure.log"; fail "configure"; }
grep -q "S2Sim_DIR:PATH=$prefix/lib/cmake/S2Sim" "$tmp/examples/CMakeCache.txt" ||
  fail "find_package(S2Sim) did not find the installed package"
"$cmake" --build "$tmp/examples" -j2 > "$tmp/build.log" || { cat "$tmp/build.log"; fail "build"; }

step "the example scene with the installed s2sim-run"
"$prefix/bin/s2sim-run" "$src/examples/scene" --plugin-path "$tmp/examples/plugins" \
  --duration 8 --log "$tmp/rover.csv" --log-period 1 --signals robots/rover/y robots/rover/yaw \
  > "$tmp/run.out" 2> "$tmp/run.err" || { cat "$tmp/run.err"; fail "s2sim-run"; }
if [ -s "$tmp/run.err" ]; then cat "$tmp/run.err"; fail "warnings from the example scene"; fi
tail -n 1 "$tmp/rover.csv"
tail -n 1 "$tmp/rover.csv" | awk -F, '{ if (!($2 > 1.0 && $3 > 1.52 && $3 < 1.62)) exit 1 }' ||
  fail "the rover did not turn to +Y and drive (last row: time, y, yaw)"

step "the embedding program"
"$tmp/examples/embed/rover_check" "$src/examples/scene" "$tmp/examples/plugins"

if [ "$mode" = install ]; then
  step "every scene of scenes/ with the installed s2sim-run, the build tree present"
  [ -d "$build/plugins" ] || fail "the build tree's plugins are missing"
  # The folders it searches: its own prefix's, never the build tree's.
  mkdir -p "$tmp/unknown"
  printf '<?xml version="1.0"?>\n<scene>\n  <plugin kind="no_such_kind"/>\n</scene>\n' \
    > "$tmp/unknown/scene.xml"
  status=0
  "$prefix/bin/s2sim-run" "$tmp/unknown" --quiet 2> "$tmp/search.err" || status=$?
  [ "$status" = 3 ] || fail "an unknown kind: exit $status, not 3"
  grep -q "^  $prefix/lib/s2sim/plugins\$" "$tmp/search.err" ||
    { cat "$tmp/search.err"; fail "the installed runner does not search its prefix"; }
  if grep -q "$build" "$tmp/search.err"; then cat "$tmp/search.err"; fail "it searches the build tree"; fi
  for scene in "$src"/scenes/*/; do
    # A free port for a remote link (cartpole_remote, firefighting_omni): another program may
    # hold its default; and no client comes, so its lock-step link need not wait long for one.
    defines=()
    grep -q "name='remote_port'" "$scene/scene.xml" && defines+=(--define remote_port=0)
    grep -q "name='remote_wait_s'" "$scene/scene.xml" && defines+=(--define remote_wait_s=0.01)
    "$prefix/bin/s2sim-run" "$scene" --duration 0.05 "${defines[@]}" > /dev/null 2> "$tmp/scene.err" ||
      { cat "$tmp/scene.err"; fail "$scene"; }
    if grep -q "$build" "$tmp/scene.err"; then cat "$tmp/scene.err"; fail "$scene: build tree searched"; fi
    echo "ok $(basename "$scene")"
  done
fi
step "done"
