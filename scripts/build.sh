#!/usr/bin/env bash
# Configures and builds everything into build/: the CLI (build/bin/probelights), the tests, the benchmarks, the
# Python module, and the add-on for every Blender platform (build/probe_lights-VERSION-PLATFORM.zip; the Windows
# and macOS modules with the toolchain of scripts/cross-toolchain.sh, prepared once).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPROBELIGHTS_BUILD_TESTS=ON -DPROBELIGHTS_BUILD_BENCHMARKS=ON \
  -DPROBELIGHTS_BUILD_PYTHON=ON "-DPROBELIGHTS_PLATFORMS=windows-x64;macos-arm64;macos-x64" >/dev/null
cmake --build build -j"$(nproc)"
