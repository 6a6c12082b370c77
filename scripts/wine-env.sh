#!/usr/bin/env bash
# Prepares (once) and prints the folder of a Windows Python for the Wine tests: the official embeddable CPython
# (from scripts/cross-toolchain.sh) with Windows wheels from PyPI unpacked beside it, and a Wine prefix.
#   scripts/wine-env.sh module 311     -> CPython 3.11 with numpy and pytest (the module's Python tests)
#   scripts/wine-env.sh bpy 4.5.15     -> Blender 4.5.15 as a Python module (PyPI's Windows bpy and what it needs)
#   scripts/wine-env.sh pip 311        -> CPython 3.11 with nothing installed and a wheelhouse/ of the Windows wheels
#                                         `pip install probelights` fetches (pip, numpy, openimageio) and pytest's
# Pinned in tests/wine/versions. Each folder holds python/ (python.exe), site-packages/ and prefix/ (WINEPREFIX);
# tests/wine/run.sh runs a script in it. Everything stays in the cache (PROBELIGHTS_CACHE, ~/.cache/probelights).
set -euo pipefail
cd "$(dirname "$0")/.."
kind=$1 version=$2
pin() { awk -v k="$1" '$1 == k {print $2}' tests/wine/versions; }
case $kind in
  module) abi=$version; requirements=("numpy==$(pin numpy-cp$abi)" "pytest==$(pin pytest)" "colorama==$(pin colorama)") ;;
  bpy)    case $version in 4.*|5.0.*) abi=311 ;; *) abi=313 ;; esac; requirements=("bpy==$version") ;;
  pip)    abi=$version
          # openimageio as pyproject.toml pins it (the package's dependency); numpy 2, which that wheel needs
          requirements=("pip==$(pin pip)" "numpy==$(pin numpy-pip)" "$(grep -o 'openimageio==[0-9.]*' pyproject.toml)"
                        "pytest==$(pin pytest)" "colorama==$(pin colorama)") ;;
  *) echo "usage: wine-env.sh module 311|313 | wine-env.sh bpy VERSION | wine-env.sh pip 311|313" >&2; exit 2 ;;
esac
command -v wine >/dev/null || { echo "wine missing: scripts/install-deps.sh --test installs it" >&2; exit 3; }
toolchain=$(scripts/cross-toolchain.sh)
cache=${PROBELIGHTS_CACHE:-$HOME/.cache/probelights}
dir=$cache/wine-$kind-$version-$(pin numpy-cp$abi)-$(pin pytest)
[[ $kind == bpy ]] && dir=$cache/wine-bpy-$version
[[ $kind == pip ]] && dir=$cache/wine-pip-$version-$(pin pip)-$(pin numpy-pip)-$(pin pytest)
if [[ -f $dir/.complete ]]; then echo "$dir"; exit 0; fi
rm -rf "$dir"; mkdir -p "$dir/site-packages"
cp -r "$toolchain/embed/cp$abi" "$dir/python"
# pip of the same CPython minor version (scripts/cpython.sh): Requires-Python is checked against it.
python=$("$(dirname "$0")"/cpython.sh "3.${abi:1}")
if [[ $kind == pip ]]; then
  # A Python as a user's is before `pip install`: its own Lib\site-packages, where pip puts packages (the
  # embeddable CPython reads sys.path from its ._pth file alone), and Scripts\ for the commands.
  printf 'python%s.zip\n.\nLib\\site-packages\nimport site\n' "$abi" > "$dir/python/python$abi._pth"
  "$python" -m pip download -q --disable-pip-version-check --dest "$dir/wheelhouse" --platform win_amd64 \
    --python-version "3.${abi:1}" --implementation cp --only-binary=:all: "${requirements[@]}" >&2
else
  # The embeddable CPython reads sys.path from its ._pth file alone (no PYTHONPATH, not the script's folder).
  printf 'python%s.zip\n.\n..\\site-packages\nimport site\n' "$abi" > "$dir/python/python$abi._pth"
  "$python" -m pip install -q --disable-pip-version-check --no-compile --target "$dir/site-packages" \
    --platform win_amd64 --python-version "3.${abi:1}" --implementation cp --only-binary=:all: \
    "${requirements[@]}" >&2
fi
export WINEPREFIX=$dir/prefix WINEDEBUG=-all WINEDLLOVERRIDES="mscoree,mshtml=;winemenubuilder.exe=d"
wineboot --init >/dev/null 2>&1 || wine wineboot --init >/dev/null 2>&1
touch "$dir/.complete"
echo "$dir"
