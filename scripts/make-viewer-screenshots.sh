#!/usr/bin/env bash
# Makes the viewer screenshots of docs/images/ with s2sim-view's own --screenshot, under Xvfb
# (Mesa llvmpipe). Run from the repository after building: scripts/make-viewer-screenshots.sh
# [BUILD_DIR]. The SimTwo base scene comes from ../shared/simtwo-scenes when present.
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$repo/build}"
view="$build/bin/s2sim-view"
out="$repo/docs/images"
shared="$repo/../shared/simtwo-scenes"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
shot() {  # shot NAME SCENE ARGS... (SCENE "-": none, a replay names its own)
  local name="$1" scene=("$2")
  [ "$2" = "-" ] && scene=()
  shift 2
  xvfb-run -a -s "-screen 0 1280x720x24" "$view" "${scene[@]}" --size 1280x720 "$@" \
    --do "screenshot $out/$name.png" --do quit >/dev/null
  echo "wrote docs/images/$name.png"
}
default="$repo/scenes/default"

shot viewer-world "$default" --do "wait 75"
shot viewer-configuration "$default" --show-window configuration --do "run-until 0.8"
# The NXT driving at 6 V: its motor speeds and currents (the chart the runner's CSV equals).
nxt="$repo/scenes/nxt"
shot viewer-nxt "$nxt" --set robots/nxt/axes/right/ref_voltage=6 \
  --set robots/nxt/axes/left/ref_voltage=-6 --do "follow nxt" --do "camera -150 30 0.8" \
  --do "run-until 1.5"
shot viewer-chart "$nxt" --set robots/nxt/axes/right/ref_voltage=6 \
  --set robots/nxt/axes/left/ref_voltage=-6 \
  --chart 'robots/nxt/axes/*/speed' 'robots/nxt/axes/*/current' --do "follow nxt" \
  --do "camera -150 30 0.8" --do "hide run" --do "run-until 3"
shot viewer-body "$default" --do "select bob" --do "run-until 0.5"
# Keep in view: the quadrotor flying its square, followed once it would leave the view.
shot viewer-quadrotor "$repo/scenes/quadrotor" --show-window log --do "camera -120 15 1.8" \
  --do "overlay trails on" --do "run-until 9"
# The boat on its water: the buoyancy's surface, a translucent plane over the floor.
shot viewer-boat "$repo/scenes/boat" --do "run-until 8" --do "camera -125 22 4.5" --do "wait 1"
# Trails, names, axes and scale bar: the NXT turning a small circle for 4 s.
shot viewer-trail "$nxt" --set robots/nxt/axes/right/ref_voltage=6 \
  --set robots/nxt/axes/left/ref_voltage=3 --show-window configuration \
  --do "overlay trails on" --do "overlay labels on" --do "run-until 4" --do "frame" --do "wait 1"
# The default layout: the Run window and the Log on the left, the Chart and the
# Sheet as tabs of the bottom row, the 3-D view framed in the rest.
shot viewer-layout "$nxt" --set robots/nxt/axes/right/ref_voltage=6 \
  --set robots/nxt/axes/left/ref_voltage=-6 --show-window log --show-window sheet \
  --chart 'robots/nxt/axes/*/speed' 'robots/nxt/axes/*/current' --do "follow nxt" \
  --do "wait 2" --do "show chart" --do "run-until 2"

# The scene editor after a typing mistake: the error and its line, the scene still running.
cp -r "$default" "$tmp/editor"
shot viewer-editor "$tmp/editor" --do "wait 2" --do "editor-open scene.xml" \
  --do "editor-insert 12 <robot oops=>" --do "click Apply" --do "wait 30"

# Sheet cells come from controllers; the kernel tests' fixture has plugins that declare some.
plugins="$build/test-plugins/scene"
if [ -d "$plugins" ]; then
  cp -r "$repo/tests/kernel/sim/fixtures/components" "$tmp/sheet"
  sed -i "s#</scene>#  <plugin kind='test_reference_controller' id='writer' input='sheet/A1' value='0.5' period_ms='40'/>\n  <plugin kind='test_echo_sensor' id='gain' input='sheet/B2'/>\n  <plugin kind='test_echo_sensor' id='offset' input='sheet/B3'/>\n  <plugin kind='test_echo_sensor' id='start' input='sheet/C1' unit='button'/>\n</scene>#" "$tmp/sheet/scene.xml"
  shot viewer-sheet "$tmp/sheet" --plugin-path "$plugins" --plugin-path "$build/plugins" --show-window sheet \
    --do "sheet-set B2 1.25" --do "sheet-set B3 -0.1" --do "run-until 1"
fi

# A SimTwo project with its author's saved camera (config_Viewer.ini, config_Params.ini), floor
# texture (ground.jpg), grid and sky.
if [ -d "$shared/Manipulator6DoF" ]; then
  shot viewer-simtwo-camera "$shared/Manipulator6DoF" --show-window log --do "run-until 0.5"
fi

if [ -d "$shared/base" ]; then
  shot viewer-simtwo-base "$shared/base" --show-window log --do "follow Classic" \
    --do "camera -120 35 2.2" --do "run-until 1"
fi

# SimTwo scripts in the viewer: compile errors, sheets, trails and XY charts. The compile cache of the tests, if built.
export S2SIM_PASCAL_CACHE="${S2SIM_PASCAL_CACHE:-$build/pascal-cache}"
if [ -d "$shared/MotorModel_V3AGM" ] && command -v fpc >/dev/null; then
  # The script editor after Compile: fpc's located error, its line shown (the project's named
  # script, control_PosCascata.pas, does not compile in SimTwo either).
  cp -r "$shared/MotorModel_V3AGM" "$tmp/motor"
  shot viewer-script-error "$tmp/motor" --show-window script --show-window log --do "wait 3" \
    --do "click Compile" --do "wait 1" --do "script-goto-error 1" --do "wait 3"
fi
if [ -d "$shared/RobotFactoryLite" ] && command -v fpc >/dev/null; then
  # RobotFactoryLite under its script with its sheet, its [Set] button pressed at 0.5 s.
  shot viewer-script-sheet "$shared/RobotFactoryLite" --show-window sheet --show-window log \
    --do "run-until 0.5" --do "click Set##C11" --do "run-until 2"
fi
if [ -d "$shared/base" ] && command -v fpc >/dev/null; then
  # A script's trail (AddTrailNode), HUD lines (HUDStrings) and WriteLn lines, and the chart's
  # XY mode: the robot's y against its x beside the script's own XY series.
  shot viewer-script-trail-xy "$shared/base" \
    --script-file "$repo/tests/apps/viewer/fixtures/trail_xy.pas" --show-window log \
    --do "chart-xy robots/Classic/x robots/Classic/y" --do "show chart" --do "run-until 4"
fi
if command -v fpc >/dev/null; then
  # SimTwo's canvases: scenes/canvas's script draws on the board's top and the sign's face.
  shot viewer-canvas "$repo/scenes/canvas" --show-window log --do "run-until 0.5" \
    --do "camera -150 35 1.1" --do "wait 1"
fi
# Shadows on bodies as well as on the floor: the pile settling, seen close.
shot viewer-shadows "$repo/scenes/pile" --hide-ui --do "run-until 2.5" --do "camera -60 25 1.4" \
  --do "wait 1"
# A replay (docs/recording.md): the NXT's curve recorded by s2sim-run, scrubbed back to 1.8 s on
# the timeline, the chart following it.
"$build/bin/s2sim-run" "$nxt" --duration 3 --log-period 0.02 --quiet --record "$tmp/nxt.s2rec" \
  --set robots/nxt/axes/right/ref_voltage=6 robots/nxt/axes/left/ref_voltage=2
shot viewer-replay - --replay "$tmp/nxt.s2rec" --paused \
  --chart 'robots/nxt/x' 'robots/nxt/y' 'robots/nxt/axes/*/speed' --do "follow nxt" \
  --do "camera -150 35 1.0" --do "replay-seek 3" --do "wait 2" --do "replay-seek 1.8" --do "wait 2"
# The Cameras window (C): the rover's camera in colour, depth (false colour, its legend) and
# body ids, the lidar's range image, and its point cloud drawn in the 3-D view.
cams="$repo/scenes/camera_lidar"
shot viewer-cameras "$cams" --do "show cameras" --do "run-until 0.35" --do "wait 2"
shot viewer-lidar "$cams" --do "show cameras" --do "camera-image robots/rover/sensors/front/rgb off" \
  --do "camera-image robots/rover/sensors/front/segmentation off" --do "camera 150 35 5.5" \
  --do "run-until 0.35" --do "wait 2"
# The camera's own images as s2sim-run --save-images writes them (the frame at 0.3 s): colour,
# depth in millimetres and body ids, both 16-bit grey.
"$build/bin/s2sim-run" "$cams" --duration 0.35 --quiet --save-images "$tmp/frames"
for image in rgb depth segmentation; do
  cp "$tmp/frames/robots/rover/sensors/front/$image/000004.png" "$out/camera-$image.png"
  echo "wrote docs/images/camera-$image.png"
done
