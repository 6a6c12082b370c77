#!/usr/bin/env bash
# Every test: install what is missing, build, run the native, CLI, Python and Blender tests (ctest runs them all).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --test
# Blender as a Python module, each pinned version in a cached virtual environment (downloads only the first time).
grep -E '^[0-9]' tests/blender/bpy-versions | while read -r version; do scripts/bpy-env.sh "$version" >/dev/null; done
# Windows' Pythons and Blenders for the Wine tests, pinned in tests/wine/versions (downloads only the first time).
scripts/wine-env.sh module 311 >/dev/null
scripts/wine-env.sh module 313 >/dev/null
grep -E '^bpy ' tests/wine/versions | while read -r _ version; do scripts/wine-env.sh bpy "$version" >/dev/null; done
scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)"
