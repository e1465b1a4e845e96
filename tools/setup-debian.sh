#!/usr/bin/env bash
# Installs every Debian 12 package FaceSketch needs to build, test and run headless.
# Idempotent: packages already present are skipped, so a second run is a no-op.
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools spirv-tools
  libglfw3-dev libglm-dev libeigen3-dev libimgui-dev catch2
  # gui: the window's MIT-SHM presentation (app/gui/x11_shm_sink.cpp): Xlib, Xext, and Xrandr for
  # GLFW's native X11 header (glfw3native.h includes it)
  libx11-dev libxext-dev libxrandr-dev
  libtinyobjloader-dev nlohmann-json3-dev libcli11-dev libstb-dev libmeshoptimizer-dev
  xvfb xauth clang-format
  # gui: real X input events for the app's tests (tests/gui/*.sh); python3 checks their results
  xdotool
  python3 python3-numpy
  # glTF export (issue 13): tinygltf writes the .glb; chromium runs three.js on it in a test
  libtinygltf-dev
  chromium
  # issue 17: the libFuzzer targets of tests/fuzz (tools/fuzz.sh, FACESKETCH_FUZZ=ON)
  clang-14
  libfuzzer-14-dev
)
# The glTF tests' real clients (tools/package.json) run on node; a node from elsewhere (with its
# own npm) is kept, else Debian's.
if ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
else
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  echo "setup: installing ${missing[*]}"
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The npm packages the glTF tests run (gltf-validator, three), pinned by tools/package-lock.json.
# Installed once into tools/node_modules (git-ignored); the tests then need no network.
tools="$(cd "$(dirname "$0")" && pwd)"
if [ ! -f "$tools/node_modules/.package-lock.json" ] || [ "$tools/package-lock.json" -nt "$tools/node_modules/.package-lock.json" ]; then
  echo "setup: npm ci in $tools"
  npm ci --prefix "$tools" --no-audit --no-fund --loglevel=error
fi
