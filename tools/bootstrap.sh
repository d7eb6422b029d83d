#!/usr/bin/env bash
# Sets vksplat up on a fresh Debian 12 machine: installs the Debian packages it needs, builds it,
# then either renders the built-in demo scene (`demo`) or runs the test suite (`test`).
# README.md explains why each package is here. Runs apt through sudo when not root.
set -euo pipefail
mode=${1:-demo}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${VKSPLAT_BUILD_DIR:-$root/build}

packages=(
  cmake g++ pkg-config
  libvulkan-dev mesa-vulkan-drivers glslang-tools libvulkan-volk-dev
  libglm-dev libeigen3-dev libopencv-dev libnanoflann-dev
  libgtest-dev libcli11-dev nlohmann-json3-dev zlib1g-dev libzstd-dev libwebp-dev libglfw3-dev
)
# The test suite also drives headless Chromium to check that the HTML reports draw.
[ "$mode" = test ] && packages+=(chromium)
# ... and opens the viewer on a virtual display, sends it keys and takes screenshots.
[ "$mode" = test ] && packages+=(xvfb xdotool imagemagick)
# ... and runs the GPU tests under the Vulkan validation layer.
[ "$mode" = test ] && packages+=(vulkan-validationlayers)
# ... and checks the .splat/.spz writers with PlayCanvas splat-transform (npm, installed below) --
# unless a Node.js with npm is there already (NodeSource's nodejs bundles npm, conflicting with Debian's).
[ "$mode" = test ] && ! command -v npm >/dev/null && packages+=(nodejs npm)
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
missing=()
for p in "${packages[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# splat-transform, pinned, in a git-ignored folder of the project (tests/io/splat_transform_test.sh
# looks there); install scripts are skipped: they fetch GPU binaries the test does not use.
splat_transform_version=2.7.1
if [ "$mode" = test ] && ! grep -qs "\"version\": \"$splat_transform_version\"" \
    "$root/.npm-tools/node_modules/@playcanvas/splat-transform/package.json"; then
  echo "installing @playcanvas/splat-transform@$splat_transform_version into .npm-tools/"
  npm install --prefix "$root/.npm-tools" --no-audit --no-fund --ignore-scripts --silent \
    "@playcanvas/splat-transform@$splat_transform_version"
fi

# The Khronos glTF validator, pinned, beside it (tests/io/gltf_validator_test.sh looks there).
gltf_validator_version=2.0.0-dev.3.10
if [ "$mode" = test ] && ! grep -qs "\"version\": \"$gltf_validator_version\"" \
    "$root/.npm-tools/node_modules/gltf-validator/package.json"; then
  echo "installing gltf-validator@$gltf_validator_version into .npm-tools/"
  npm install --prefix "$root/.npm-tools" --no-audit --no-fund --ignore-scripts --silent \
    "gltf-validator@$gltf_validator_version"
fi

# A unity build (CMake joins a target's sources, a few at a time, into one file): the set-up builds
# everything from nothing, and most of a file's compile time goes to headers every file includes
# (Vulkan, GLM, OpenCV, nlohmann/json, CLI11, GoogleTest). On 2 cores: about 12 min -> 397 s. Developers'
# own builds may leave it off, so that a change recompiles one file. -O2 (Debian's own level) rather
# than Release's -O3: the work is on the GPU, and -O3 took a fifth longer to compile (23.5 s against
# 19.3 s for one of vksplat_io's unity files).
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" \
  -DCMAKE_UNITY_BUILD=ON >/dev/null
cmake --build "$build" -j"$(nproc)"

case "$mode" in
  demo) "$build/tools/vksplat" demo --out "${2:-$root/demo_out}" --force ;;
  test) ctest --test-dir "$build" --output-on-failure -j"$(nproc)" ;;
  *) echo "usage: $0 demo [OUT_DIR] | test" >&2; exit 2 ;;
esac
