#!/usr/bin/env bash
# Installs every Debian 12 package that anyphys' build, tests and tools need.
# Idempotent: when everything is already installed it does nothing (no apt-get at all).
# Usage: scripts/setup.sh [--fuzz]
#   --fuzz  also clang and libFuzzer, for the fuzz targets (scripts/fuzz.sh)
set -euo pipefail

with_fuzz=0
case "${1:-}" in
  "") ;;
  --fuzz) with_fuzz=1 ;;
  *) echo "usage: scripts/setup.sh [--fuzz]" >&2; exit 2 ;;
esac

packages=(
  build-essential    # g++ 12, make, libc headers
  cmake              # >= 3.25
  ninja-build
  pkg-config         # ODE and Bullet are found through pkg-config
  libeigen3-dev      # Eigen 3.4: math types of the API
  nlohmann-json3-dev # scene files
  libcli11-dev       # the anyphys command-line tool
  libgtest-dev       # GoogleTest 1.12
  libgmock-dev
  libbenchmark-dev   # Google Benchmark 1.7
  libode-dev         # ODE 0.16 (double precision), backend
  libbullet-dev      # Bullet 3.24, backend
  libbox2d-dev       # Box2D 2.4, backend
  gnuplot-nox        # plots of `anyphys report` (PNG and SVG through the cairo terminals)
  libglfw3-dev       # the testbed's window and input (GLFW 3.3)
  libimgui-dev       # the testbed's panels: Dear ImGui 1.86 with its GLFW and OpenGL 3 backends (static)
  libglew-dev        # the testbed's OpenGL 3.3 core function loader
  libpng-dev         # the testbed's screenshots and recorded frames
  xvfb               # xvfb-run: the testbed's headless renders and tests on a machine without a display
  xauth              # needed by xvfb-run
  libgl1-mesa-dri    # Mesa's software OpenGL (llvmpipe) under Xvfb
  libglx-mesa0
  ffmpeg             # the testbed's --video FILE.mp4 / .gif
)
if [[ $with_fuzz -eq 1 ]]; then
  packages+=(
    clang              # clang 14: the libFuzzer targets of tests/fuzz
    libclang-rt-14-dev # libFuzzer and clang's sanitizer runtimes
  )
fi

missing=()
for pkg in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  if [[ "$status" != "install ok installed" ]]; then
    missing+=("$pkg")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

echo "setup: installing ${missing[*]}"
if [[ $(id -u) -eq 0 ]]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1; then
  sudo=(sudo)
else
  echo "setup: error: missing packages (${missing[*]}); run as root or install sudo" >&2
  exit 1
fi
if ! command -v apt-get >/dev/null 2>&1; then
  echo "setup: error: apt-get not found; this script targets Debian 12" >&2
  exit 1
fi

export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
echo "setup: done"
