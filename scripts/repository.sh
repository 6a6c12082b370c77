#!/usr/bin/env bash
# Writes a static Blender extensions repository: the given zips and Blender's own listing of them (index.json,
# index.html), made by Blender's `server-generate` (blender_ext.py of the newest pinned Blender, addon/extension-tools).
# The folder is written whole or not at all (beside it, then renamed over it). Hosted on any static web server, or
# used as it is by its file:// URL: Blender 4.2+ > Preferences > Get Extensions > Repositories > Add Remote Repository.
#   scripts/repository.sh OUT_DIR ZIP [ZIP ...]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
out=$1; shift
(($#)) || { echo "repository.sh: no zips given" >&2; exit 2; }
version=$(awk '$1 == "newest" {print $2}' "$here/addon/extension-tools")
tool=$("$here/scripts/blender-ext.sh" "$version")
partial=$(dirname "$out")/.$(basename "$out").partial
rm -rf "$partial"; mkdir -p "$partial"
cp "$@" "$partial/"
# Its messages go to stderr; a zip it refuses is an error line, so any "error" fails the build.
log=$(python3 "$tool/blender_ext.py" server-generate --repo-dir "$partial" --html 2>&1) ||
  { echo "$log" >&2; exit 1; }
if grep -qi "error" <<<"$log"; then echo "$log" >&2; exit 1; fi
[[ -f $partial/index.json && -f $partial/index.html ]] || { echo "$log" >&2; exit 1; }
rm -rf "$out.old"
[[ -e $out ]] && mv "$out" "$out.old"
mv "$partial" "$out"
rm -rf "$out.old"
