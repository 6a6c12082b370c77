#!/usr/bin/env bash
# Every test: install what is missing, build, run the native, CLI, Python and Blender tests (ctest runs them all).
#   bash scripts/test.sh           every tier (what the README's test command and CI run)
#   bash scripts/test.sh --quick   the inner loop: unit, CLI, Python and the add-on in Debian's Blender (ctest -L quick)
set -euo pipefail
cd "$(dirname "$0")/.."
quick=false
case "${1:-}" in
  "") ;;
  --quick) quick=true ;;
  *) echo "usage: bash scripts/test.sh [--quick]" >&2; exit 2 ;;
esac
scripts/install-deps.sh --test
scripts/usd-env.sh >/dev/null  # usd-core for the USD read-back test (downloads only the first time)
# Blender's own extension tool of the oldest and newest pinned Blender (validate, server-generate): the build
# writes build/repository with it and the tests validate every zip with both (addon/extension-tools).
awk '!/^#/ && NF {print $2}' addon/extension-tools | while read -r version; do scripts/blender-ext.sh "$version" >/dev/null; done
if ! $quick; then
  # Blender as a Python module, each pinned version in a cached virtual environment (downloads only the first time).
  grep -E '^[0-9]' tests/blender/bpy-versions | while read -r version; do scripts/bpy-env.sh "$version" >/dev/null; done
  # and the oldest Blender with extensions (addon/extension-tools), where the repository test runs too.
  scripts/bpy-env.sh "$(awk '$1 == "oldest" {print $2}' addon/extension-tools)" >/dev/null
  # Windows' Pythons and Blenders for the Wine tests, pinned in tests/wine/versions (downloads only the first time).
  scripts/wine-env.sh module 311 >/dev/null
  scripts/wine-env.sh module 313 >/dev/null
  scripts/wine-env.sh pip 311 >/dev/null  # and a bare one with the wheels `pip install probelights` fetches
  scripts/wine-env.sh pip 313 >/dev/null
  grep -E '^bpy ' tests/wine/versions | while read -r _ version; do scripts/wine-env.sh bpy "$version" >/dev/null; done
fi
scripts/build.sh
cd build
if $quick; then
  ctest --output-on-failure -j"$(nproc)" -L quick
else
  ctest --output-on-failure -j"$(nproc)"
fi
