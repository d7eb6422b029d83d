#!/usr/bin/env bash
# Installs vksplat into a scratch prefix, then builds examples/find_package against it twice:
# with CMake's find_package(vksplat) and with pkg-config, and runs both on a scene made by the
# installed CLI; and builds and runs examples/embed against it too. usage: install_test.sh BUILD_DIR SOURCE_DIR WORK_DIR
set -euo pipefail
build=$1
source=$2
work=$3
rm -rf "$work" && mkdir -p "$work"
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" >/dev/null
for f in include/vksplat/render/renderer.hpp include/vksplat/vksplat.h lib/libvksplat.a lib/cmake/vksplat/vksplatConfig.cmake \
         lib/cmake/vksplat/vksplatConfigVersion.cmake lib/cmake/vksplat/vksplatTargets.cmake \
         lib/pkgconfig/vksplat.pc bin/vksplat; do
  [ -e "$prefix/$f" ] || { echo "FAILED: $f was not installed"; exit 1; }
done
"$prefix/bin/vksplat" demo --out "$work/demo" --views 1 --width 32 --height 24 >/dev/null

# CMake: find_package(vksplat) + vksplat::vksplat.
cmake -S "$source/examples/find_package" -B "$work/cmake_build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/cmake_build" >/dev/null
"$work/cmake_build/render_scene" "$work/demo/demo.ply" "$work/cmake.png" 64 48

# The embedding example against the installed package, with the application's own Vulkan loader.
cmake -S "$source/examples/embed" -B "$work/embed_build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/embed_build" >/dev/null
"$work/embed_build/embed_example"

# The C API from a C program against the installed package, on the demo scene as well as its own.
cmake -S "$source/examples/c_api" -B "$work/c_api_build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/c_api_build" >/dev/null
bash "$source/tests/capi/c_example_test.sh" "$work/c_api_build/c_api_example" "$work/c_api_run" "$work/demo/demo.ply"

# pkg-config, linking the system Vulkan loader as well: vksplat's private copy of volk must not
# clash with the application's Vulkan symbols.
PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --exists vksplat
c++ -O1 -o "$work/pkg_config_render" "$source/examples/find_package/main.cpp" \
    $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs vksplat)
"$work/pkg_config_render" "$work/demo/demo.ply" "$work/pkg_config.png" 64 48
echo "install: find_package, pkg-config, embed and C API builds all render"
