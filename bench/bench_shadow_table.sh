#!/usr/bin/env bash
# bench/bench_shadow_estimate.py on every probe here (../shared/hdri and Blender's 8 studio lights) in one Blender:
#   bench/bench_shadow_table.sh PYTHON_OR_BLENDER [SHARED]      e.g. blender, ~/.cache/probelights/bpy-4.5.15/bin/python
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
runner=$1 shared=${2:-$here/../shared}
for probe in "$shared"/hdri/*.hdr "$shared"/hdri/*.exr /usr/share/blender/datafiles/studiolights/world/*.exr; do
  [[ -f $probe ]] || continue
  bash "$here/tests/blender/run.sh" "$runner" "$here/bench/bench_shadow_estimate.py" "$here/build/probe_lights-0.1.0-linux_x64.zip" \
    "$shared" "$probe" | grep '^ESTIMATE'
done
