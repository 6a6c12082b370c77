#!/usr/bin/env bash
# Fails when a C++ file of the tree does not match .clang-format (Debian 12's clang-format 14; comments are not
# reflowed: formula blocks are laid out by hand), or has a line over 110 columns. Run by ctest as "format".
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "clang-format is missing: scripts/install-deps.sh --test"; exit 1; }
mapfile -t files < <(git ls-files --cached --others --exclude-standard 'native/*.cpp' 'native/*.h' 'tests/native/*.cpp' 'tests/native/*.h')
clang-format --dry-run --Werror "${files[@]}"
long=$(awk 'length($0) > 110 {print FILENAME ":" FNR}' "${files[@]}")
if [[ -n $long ]]; then echo "lines over 110 columns:"; echo "$long"; exit 1; fi
echo "${#files[@]} files formatted"
