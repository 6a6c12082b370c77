#!/usr/bin/env bash
# Every test: install what is missing, build, run the native, CLI, Python and Blender tests (ctest runs them all).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --test
scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)"
