#!/usr/bin/env bash
# Installs every Debian 12 package FaceSketch needs to build, test and run headless.
# Idempotent: packages already present are skipped, so a second run is a no-op.
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools spirv-tools
  libglfw3-dev libglm-dev libeigen3-dev libimgui-dev catch2
  libtinyobjloader-dev nlohmann-json3-dev libcli11-dev libstb-dev libmeshoptimizer-dev
  xvfb xauth clang-format
  # issue 17: the libFuzzer targets of tests/fuzz (tools/fuzz.sh, FACESKETCH_FUZZ=ON)
  clang-14
  libfuzzer-14-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
echo "setup: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
