#!/usr/bin/env bash
# A Blender test file in PyPI's Windows bpy under Wine, in a fresh profile into which the add-on is installed from
# the Windows zip as a user would (Get Extensions > Install from Disk: harness.install_addon).
#   tests/wine/blender_tests.sh BPY_VERSION BUILD_DIR TEST.py [harness arguments, e.g. --only test_a,test_b]
set -euo pipefail
version=$1 build=$(cd "$2" && pwd) test=$(cd "$(dirname "$3")" && pwd)/$(basename "$3")
shift 3
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
env=$(bash "$repo/scripts/wine-env.sh" bpy "$version")
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
export WINEPREFIX=$env/prefix WINEDEBUG=-all
windows() {  # Blender takes its profile folders as Windows paths
  local path
  path=$(winepath -w "$1" 2>/dev/null) && [[ -n $path ]] || { echo "winepath failed on $1" >&2; exit 1; }
  echo "$path"
}
profile_env=()
for kind in scripts config extensions datafiles; do
  profile_env+=("--env=BLENDER_USER_${kind^^}=$(windows "$profile/$kind")")
done
if [[ -n ${PROBELIGHTS_RENDER_CACHE:-} ]]; then  # the render tests' Cycles renders remembered (harness/render_cache.py)
  mkdir -p "$PROBELIGHTS_RENDER_CACHE"
  profile_env+=("--env=PROBELIGHTS_RENDER_CACHE=$(windows "$PROBELIGHTS_RENDER_CACHE")")
fi
package=$(sed -n 's/^version = "\(.*\)"/\1/p' "$repo/addon/probe_lights/blender_manifest.toml")
bash "$here/run.sh" "$env" "${profile_env[@]}" "$test" -- \
  --zip "$(windows "$build/probe_lights-$package-windows_x64.zip")" --shared "$(windows "$repo/../shared")" "$@"
