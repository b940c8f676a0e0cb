#!/bin/bash
# The Debian package as a user gets it (tests/package/CMakeLists.txt): built with cpack from
# the build tree without touching the source tree, its control fields (Depends python3 and
# python3-numpy, Recommends fpc), unpacked into a fresh root with dpkg -x (as root or not, no
# chroot), and run from there with neither tree in sight: `s2sim-run default` by name from
# another folder, a misspelt name's error, `import s2sim` with a scene, and a SimTwo project
# under its script (skipped, saying why, when ../shared is absent or fpc is missing).
#   deb_root_test.sh BUILD_DIR SOURCE_DIR CPACK VERSION SHARED_SCENES
set -euo pipefail
build=$1 src=$2 cpack=$3 version=$4 shared=$5
tmp=$(mktemp -d "${TMPDIR:-/tmp}/s2sim-$$.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
unset S2SIM_PLUGIN_PATH S2SIM_SCENE_PATH PYTHONPATH
fail() { echo "FAIL: $*" >&2; exit 1; }
step() { echo "== $* ($(date +%s.%N | cut -c1-14))"; }

step "the README's cpack command, run from the source tree"
# It must leave the source tree as it was: cpack writes where it runs unless told otherwise
# (the package, _CPack_Packages), so the folder it runs in must hold the same entries after;
# the package and cpack's staging install go to build/package. (Not all of git status: other
# tests run meanwhile.)
tree_before=$(ls -A "$src")
rm -f "$build"/package/s2sim_*.deb
(cd "$src" && "$cpack" -G DEB --config "$build/CPackConfig.cmake" > "$tmp/cpack.log" 2>&1) ||
  { cat "$tmp/cpack.log"; fail "cpack"; }
tree_after=$(ls -A "$src")
[ "$tree_before" = "$tree_after" ] ||
  { diff <(echo "$tree_before") <(echo "$tree_after") || true; fail "cpack changed the source tree"; }
deb=$(ls "$build"/package/s2sim_*.deb)
echo "package: $(basename "$deb"), $(du -k "$deb" | cut -f1) kB"

step "control fields"
depends=$(dpkg-deb -f "$deb" Depends)
recommends=$(dpkg-deb -f "$deb" Recommends)
echo "Depends: $depends"
echo "Recommends: $recommends"
[ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || fail "the package's version is not $version"
python_minor=$(/usr/bin/python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])')
for want in "python3 (>= $python_minor)" "python3-numpy" "libsimbody"; do
  [[ ", $depends," == *", $want"* ]] || fail "Depends lacks '$want'"
done
[[ ", $recommends," == *", fpc,"* ]] || fail "Recommends lacks fpc"

step "dpkg -x into a fresh root"
root=$tmp/root
dpkg -x "$deb" "$root"
for f in usr/bin/s2sim-run usr/bin/s2sim-view usr/share/s2sim/scenes/default/scene.xml \
         usr/share/s2sim/scenes/nxt/scene.xml usr/share/s2sim/examples/CMakeLists.txt \
         usr/share/s2sim/examples/python/nxt_pid.py usr/share/doc/s2sim/README.md \
         usr/share/doc/s2sim/docs/recording.md usr/lib/python3/dist-packages/s2sim/recording.py; do
  [ -e "$root/$f" ] || fail "/$f is not in the package"
done
mkdir "$tmp/elsewhere"
cd "$tmp/elsewhere"  # neither tree, no scenes/ folder here

step "s2sim-run default, found by name in the package's scenes"
"$root/usr/bin/s2sim-run" default --duration 0.2 --summary summary.json --no-timing \
  > run.out 2> run.err || { cat run.err; fail "s2sim-run default"; }
grep -q '"sim_time": 0.2' summary.json || { cat summary.json; fail "the run did not last 0.2 s"; }
if grep -qF -e "$build" -e "$src" run.err run.out; then
  cat run.err; fail "the installed runner reached the build or source tree"
fi
status=0
"$root/usr/bin/s2sim-run" defualt --quiet 2> misspelt.err || status=$?
[ "$status" = 2 ] || fail "a misspelt scene: exit $status, not 2"
grep -qF "$root/usr/share/s2sim/scenes/defualt" misspelt.err &&
  grep -qF "scenes in $root/usr/share/s2sim/scenes: blimp blimp_serial boat" misspelt.err ||
  { cat misspelt.err; fail "the error does not say where it looked and what is there"; }
cat misspelt.err

step "the package's Python module with the package's scene"
PYTHONPATH=$root/usr/lib/python3/dist-packages /usr/bin/python3 -c '
import sys, s2sim, numpy
from s2sim import recording
assert s2sim.__file__.startswith(sys.argv[1]), s2sim.__file__
s = s2sim.Simulation(sys.argv[1] + "/usr/share/s2sim/scenes/nxt")
s.step(20)
print("python: t =", s.time, "signals", len(s.signals("robots/nxt/*")))
' "$root" || fail "import s2sim from the package"

if [ ! -d "$shared" ]; then
  echo "SKIP the SimTwo project: $shared is absent (SimTwo's scenes beside the clone)"
elif ! command -v fpc > /dev/null; then
  echo "SKIP the SimTwo project: fpc is missing (the package Recommends it)"
else
  step "a SimTwo project under its script, with the package's runner and pascal_script plugin"
  export S2SIM_PASCAL_CACHE=$tmp/pascal-cache
  cp -r "$shared/RobotFactoryLite" project  # a script may write beside itself
  "$root/usr/bin/s2sim-run" project --duration 0.3 --log script.csv --log-period 0.1 \
    --signals controllers/script/calls controllers/script/error > script.out 2> script.err ||
    { cat script.err; fail "the SimTwo project"; }
  tail -n 1 script.csv
  tail -n 1 script.csv | awk -F, '{ if (!($2 > 0 && $3 == 0)) exit 1 }' ||
    fail "the script did not run (last row: time, calls, error)"
fi
step "done"
