#!/usr/bin/env bash
# Creates (once) and prints the path of a virtual environment holding one pinned Blender-as-a-module (bpy) from PyPI.
#   scripts/bpy-env.sh 4.5.15      -> prints ~/.cache/probelights/bpy-4.5.15 (its bin/python runs that Blender)
# Each bpy wheel is built for one CPython: 4.x and 5.0 for 3.11, 5.1+ for 3.13. The environments live outside the
# repository (PROBELIGHTS_CACHE, default ~/.cache/probelights) so a second run downloads nothing. Beside bpy, the
# render comparisons' HDR-FLIP (NVIDIA's flip-evaluator, harness/render_scene.py), pinned here.
set -euo pipefail
version=$1
extras="flip-evaluator==1.7"
py=$(bash "$(dirname "$0")/lib/bpy-python.sh" "$version")
cache=${PROBELIGHTS_CACHE:-$HOME/.cache/probelights}
env=$cache/bpy-$version
if [[ -x $env/bin/python && -f $env/.complete ]]; then
  if [[ $(cat "$env/.complete") != "$extras" ]]; then  # an environment made before the extras changed
    "$env/bin/python" -m pip install -q --disable-pip-version-check $extras >&2
    echo "$extras" >"$env/.complete"
  fi
  echo "$env"; exit 0
fi

# A CPython of the right minor version (pyenv's, the system's, or one built into the cache: scripts/cpython.sh).
python=$("$(dirname "$0")"/cpython.sh "$py")

rm -rf "$env"; mkdir -p "$cache"
"$python" -m venv "$env" >&2
"$env/bin/python" -m pip install -q --disable-pip-version-check "bpy==$version" $extras >&2
"$env/bin/python" -c "import bpy; print('bpy', bpy.app.version_string, file=__import__('sys').stderr)"
echo "$extras" >"$env/.complete"
echo "$env"
