#!/usr/bin/env bash
# Unpacks (once) a pinned pybind11 from PyPI into the cache and prints its CMake package directory.
# PyPI's and not Debian's (2.10): the add-on's modules run on CPython 3.13 and NumPy 2 (bpy 5.1+), which
# pybind11 supports from 2.12/2.13 on. pybind11 is header-only: the wheel is only unpacked, nothing installed.
set -euo pipefail
version=2.13.6
cache=${PROBELIGHTS_CACHE:-$HOME/.cache/probelights}
dir=$cache/pybind11-$version
if [[ ! -f $dir/.complete ]]; then
  rm -rf "$dir"; mkdir -p "$dir"
  python3 -m pip download -q --disable-pip-version-check --no-deps --only-binary=:all: -d "$dir" \
    "pybind11==$version" >&2
  python3 -c "import sys, zipfile, glob; zipfile.ZipFile(glob.glob(sys.argv[1] + '/*.whl')[0]).extractall(sys.argv[1])" "$dir"
  touch "$dir/.complete"
fi
echo "$dir/pybind11/share/cmake/pybind11"
