#!/usr/bin/env bash
# Installs the Debian packages S2Sim builds against. Idempotent: only missing packages are
# installed, and nothing is downloaded when everything is present. fpc (Free Pascal) compiles
# SimTwo projects' control.pas scripts (docs/scripting.md); binutils' addr2line names the line
# of a script's run-time error. libavcodec (with libavformat and libswscale) writes s2sim-view's
# MP4 videos of a replay (docs/recording.md); without it the viewer builds without --video.
# libmujoco-dev, libode-dev, libbullet-dev and libdart-dev (with its ODE collision detector,
# libdart-collision-ode-dev) are the peers of s2sim-peers (docs/benchmarks-peers.md).
# libpng writes s2sim-run's --save-images frames.
# libcairo2 (Cairo) rasterises the SimTwo scripts' canvases (docs/scripting.md, "Canvases").
# libsodium computes the remote link's HMAC of each datagram (docs/remote.md).
# libjpeg62-turbo-dev encodes camera_stream's JPEG frames (and decodes them in its test);
# libzmq3-dev gives it SimTwo's ZeroMQ PUB socket of raw frames (optional at build time).
# libegl-dev, libegl-mesa0 and libgl1-mesa-dri draw the cameras headless: OpenGL through EGL
# with no display server (docs/rendering.md).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libsimbody-dev libeigen3-dev libboost-dev libboost-filesystem-dev
  libfcl-dev libassimp-dev
  liburdfdom-dev libsdformat-dev libqhull-dev
  libimgui-dev libglfw3-dev libstb-dev
  libpng-dev
  libcairo2-dev
  libegl-dev libegl-mesa0 libgl1-mesa-dri
  libgtest-dev libbenchmark-dev
  libmujoco-dev libode-dev libbullet-dev libdart-dev libdart-collision-ode-dev
  xvfb xauth
  gnuplot-nox
  python3 pybind11-dev python3-dev python3-numpy python3-pytest python3-dask python3-distributed
  fpc binutils
  libavcodec-dev libavformat-dev libswscale-dev
  libsodium-dev
  libjpeg62-turbo-dev libzmq3-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
