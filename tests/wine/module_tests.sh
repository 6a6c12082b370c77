#!/usr/bin/env bash
# The Windows module's Python tests, run under Wine in the official embeddable CPython of one ABI (311 or 313):
# tests/python/test_module.py and test_sequence.py (what needs no files or CLI), test_same_results.py (the Linux build's lights and errors,
# within the C libraries' last bits) and the add-on's bpy-free rules, with the module taken out of the Windows zip
# as a user gets it.
#   tests/wine/module_tests.sh ABI BUILD_DIR
set -euo pipefail
abi=$1 build=$(cd "$2" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
env=$(bash "$repo/scripts/wine-env.sh" module "$abi")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
version=$(sed -n 's/^version = "\(.*\)"/\1/p' "$repo/addon/probe_lights/blender_manifest.toml")
python3 -c "import sys, zipfile; zipfile.ZipFile(sys.argv[1]).extract(sys.argv[2], sys.argv[3])" \
  "$build/probe_lights-$version-windows_x64.zip" "probe_lights/_probelights.cp$abi-win_amd64.pyd" "$work"
# The reference: the same bakes by the Linux build (the full module; test_portable_module.py shows the add-on's
# Linux modules give its bits).
PYTHONPATH=$build/python python3 "$repo/tests/python/test_same_results.py" "$work/reference.json"
cd "$repo"
PROBELIGHTS_MODULE_DIR=$work/probe_lights PROBELIGHTS_REFERENCE=$work/reference.json \
  bash "$here/run.sh" "$env" -m pytest -q -p no:cacheprovider -s tests/python/test_module.py \
  tests/python/test_sequence.py tests/python/test_same_results.py tests/python/test_world_graph.py tests/python/test_text_fit.py
