#!/usr/bin/env bash
# Builds the Python package's wheels for Windows or macOS (CPython 3.11 and 3.13) on this Linux machine: the
# package's modules in the zig sub-build of the add-on's modules for that platform (build/platforms/PLATFORM,
# cmake/zig-toolchain.cmake; configured here if the main build has not: the portable core is compiled once for
# both), their files read and written by the openimageio wheel's Python binding (python/CMakeLists.txt), each
# wrapped in a wheel with the Linux wheels' metadata (scripts/lib/platform_wheel.py).
#   scripts/wheel_platform.sh windows-x64|macos-arm64|macos-x64 OUT_DIR    -> prints the wheels' paths
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
platform=$1 out=$2
case $platform in
  windows-x64) tag=win_amd64 ;;
  macos-arm64) tag=macosx_11_0_arm64 ;;   # zig's deployment target (cmake/zig-toolchain.cmake)
  macos-x64)   tag=macosx_11_0_x86_64 ;;
  *) echo "usage: wheel_platform.sh windows-x64|macos-arm64|macos-x64 OUT_DIR" >&2; exit 2 ;;
esac
cross=$("$root/scripts/cross-toolchain.sh")
build=$root/build/platforms/$platform
# The arguments of the main build's sub-build (addon/CMakeLists.txt, ExternalProject_Add).
[[ -f $build/CMakeCache.txt ]] ||
  cmake -S "$root" -B "$build" -DCMAKE_TOOLCHAIN_FILE="$root/cmake/zig-toolchain.cmake" -DCMAKE_BUILD_TYPE=Release \
    -DPROBELIGHTS_PLATFORM="$platform" -DPROBELIGHTS_CROSS="$cross" >/dev/null
cmake --build "$build" -j"$(nproc)" --target _probelights_package_py311 _probelights_package_py313 >&2
# The wheel's metadata as pyproject.toml's backend writes it for the Linux wheels (no compile: PEP 517's
# prepare_metadata_for_build_wheel, in an isolated environment as pip's).
metadata=$(mktemp -d)
trap 'rm -rf "$metadata"' EXIT
dist_info=$("$("$root/scripts/lib/build-env.sh")" - "$root" "$metadata" <<'PY'
import sys
from build import ProjectBuilder
from build.env import DefaultIsolatedEnv
with DefaultIsolatedEnv() as env:
    builder = ProjectBuilder.from_isolated_env(env, sys.argv[1])
    env.install(builder.build_system_requires)
    env.install(builder.get_requires_for_build("wheel"))
    print(builder.metadata_path(sys.argv[2]))
PY
)
dist_info=${dist_info##*$'\n'}  # its last line (the backend says what it runs first)
for abi in 311 313; do
  if [[ $platform == windows-x64 ]]; then module=$build/package/_probelights.cp$abi-win_amd64.pyd
  else module=$build/package/_probelights.cpython-$abi-darwin.so; fi
  python3 "$root/scripts/lib/platform_wheel.py" "$module" "$dist_info" "cp$abi-cp$abi-$tag" "$out"
done
