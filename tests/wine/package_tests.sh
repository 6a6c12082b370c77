#!/usr/bin/env bash
# `pip install probelights` on Windows as a user meets it, under Wine: the package's Windows wheel for one CPython
# (scripts/wheel_platform.sh) installed by pip into a fresh official embeddable CPython with nothing else (pip
# brings numpy and openimageio, offline from the pinned wheelhouse of scripts/wine-env.sh pip), then
# tests/package/test_windows_package.py run there against this build's lights (written here by build/bin).
#   tests/wine/package_tests.sh ABI BUILD_DIR [WHEEL_DIR]    (WHEEL_DIR: wheels built already)
set -euo pipefail
abi=$1 build=$(cd "$2" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
env=$(bash "$repo/scripts/wine-env.sh" pip "$abi")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [[ -n ${3:-} ]]; then wheel=$(ls "$3"/probelights-*-cp$abi-cp$abi-win_amd64.whl)
else wheel=$(bash "$repo/scripts/wheel_platform.sh" windows-x64 "$work/dist" | grep "cp$abi-win_amd64"); fi
# The references: the same bakes by the Linux build.
mkdir "$work/reference"
"$build/bin/probelights" bake "$repo/assets/noon_grass_1k.hdr" --lights 16 -q -o "$work/reference/16.json"
"$build/bin/probelights" bake "$repo/assets/noon_grass_1k.hdr" --lights 32 --refit --evaluate -q \
  -o "$work/reference/32_refit.json"
cp -r "$env/python" "$work/python"
export WINEPREFIX=$env/prefix WINEDEBUG=-all WINEDLLOVERRIDES="mscoree,mshtml=;winemenubuilder.exe=d"
export PYTHONIOENCODING=utf-8 PYTHONUNBUFFERED=1 PIP_DISABLE_PIP_VERSION_CHECK=1
# Wine's console python.exe cannot write to a plain file: its output goes through a pipe; CRs are dropped.
win() { wine "$@" </dev/null 2>&1 | tr -d '\r'; return "${PIPESTATUS[0]}"; }
# Wine 8's gaps (tests/wine/wine_gaps.py), patched in every Python process of this one as run.sh does (pip's too:
# Python 3.13's platform module asks WMI, which ends the process under Wine 8).
mkdir -p "$work/python/Lib/site-packages"
cp "$here/wine_gaps.py" "$here/sitecustomize.py" "$work/python/Lib/site-packages/"
pip_wheel=$(ls "$env"/wheelhouse/pip-*.whl)
win "$work/python/python.exe" "$pip_wheel/pip" install -q --no-index --find-links "$env/wheelhouse" \
  --no-warn-script-location "$wheel" pytest | grep -v '^WARNING: Location' || true
test -f "$work/python/Scripts/probelights.exe" || { echo "pip did not install the probelights command" >&2; exit 1; }
cd "$work"
PROBELIGHTS_REPO=$repo PROBELIGHTS_REFERENCE=$work/reference PROBELIGHTS_WHEEL=$wheel \
  WINEPATH="$work/python/Scripts" win "$work/python/python.exe" -m pytest -q -p no:cacheprovider \
  "$repo/tests/package/test_windows_package.py"
