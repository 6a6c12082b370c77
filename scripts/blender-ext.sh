#!/usr/bin/env bash
# Prints (after caching it once) a folder holding Blender's own extension tool of one pinned Blender version:
# blender_ext.py (what `blender --command extension validate|build|server-generate` and extensions.blender.org run)
# and tags.py (the tags Blender accepts, which `blender --command extension` passes it as --valid-tags).
#   scripts/blender-ext.sh 4.2.23   -> ~/.cache/probelights/blender-ext-4.2.23
# Run it as `python3 DIR/blender_ext.py validate ZIP --valid-tags DIR/tags.py`. Both files come from PyPI's bpy
# wheel of that version (the cached bpy environment of scripts/bpy-env.sh where there is one, else the wheel,
# downloaded through pip with this machine's configuration, only these two files kept).
set -euo pipefail
version=$1
py=$(bash "$(dirname "$0")/lib/bpy-python.sh" "$version")
cache=${PROBELIGHTS_CACHE:-$HOME/.cache/probelights}
dir=$cache/blender-ext-$version
if [[ -f $dir/.complete ]]; then echo "$dir"; exit 0; fi
work=$dir.partial
rm -rf "$work" "$dir"; mkdir -p "$work"
scripts=$(ls -d "$cache/bpy-$version"/lib/python*/site-packages/bpy/*/scripts 2>/dev/null | head -1 || true)
if [[ -z $scripts ]]; then
  python3 -m pip download -q --disable-pip-version-check --no-deps --only-binary=:all: \
    --platform manylinux_2_28_x86_64 --python-version "$py" --implementation cp "bpy==$version" -d "$work/dl" >&2
  python3 - "$work" <<'PY'
import glob, re, sys, zipfile
work = sys.argv[1]
wanted = {r"bpy/[0-9.]+/scripts/addons_core/bl_pkg/cli/blender_ext\.py": "blender_ext.py",
          r"bpy/[0-9.]+/scripts/modules/_bpy_internal/extensions/tags\.py": "tags.py"}
with zipfile.ZipFile(glob.glob(work + "/dl/*.whl")[0]) as z:
    for name in z.namelist():
        for pattern, target in wanted.items():
            if re.fullmatch(pattern, name):
                open(work + "/" + target, "wb").write(z.read(name))
PY
  rm -rf "$work/dl"
else
  cp "$scripts/addons_core/bl_pkg/cli/blender_ext.py" "$scripts/modules/_bpy_internal/extensions/tags.py" "$work/"
fi
[[ -f $work/blender_ext.py && -f $work/tags.py ]] || { echo "blender-ext.sh: bpy $version has no blender_ext.py" >&2; exit 1; }
touch "$work/.complete"
mv "$work" "$dir"
echo "$dir"
