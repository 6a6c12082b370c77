#!/usr/bin/env bash
# Everything a release publishes, into build/release/ (written whole: beside it, then renamed over it):
#   probe_lights-VERSION-PLATFORM.zip   the add-on for each Blender platform (upload to extensions.blender.org)
#   repository/                         a static extensions repository of those zips (any static web host)
#   probelights-VERSION-*.whl, .tar.gz  the Python package's wheels (CPython 3.11, 3.13; Linux, Windows, macOS
#                                       arm64 and x86_64) and sdist (PyPI)
#   SHA256SUMS                          of every file above
# The version is the add-on manifest's (addon/probe_lights/blender_manifest.toml), the one place it is written.
# Nothing here uploads. Run after `bash scripts/test.sh` (or on its own: it builds what it needs).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
scripts/install-deps.sh --test
awk '!/^#/ && NF {print $2}' addon/extension-tools | while read -r version; do scripts/blender-ext.sh "$version" >/dev/null; done
scripts/build.sh
version=$(sed -n 's/^version = "\(.*\)"$/\1/p' addon/probe_lights/blender_manifest.toml)
[[ $(build/bin/probelights --version) == "probelights $version" ]] ||
  { echo "release.sh: build/bin/probelights is not version $version" >&2; exit 1; }
out=build/release partial=build/.release.partial
rm -rf "$partial"; mkdir -p "$partial"
cp build/probe_lights-"$version"-*.zip "$partial/"
cp -r build/repository "$partial/repository"
for python in 3.11 3.13; do
  scripts/wheel.sh "$(scripts/cpython.sh "$python")" "$partial" >/dev/null
done
for platform in windows-x64 macos-arm64 macos-x64; do
  scripts/wheel_platform.sh "$platform" "$partial" >/dev/null
done
# The sdist, made by the same backend (pip's build isolation brings scikit-build-core).
"$(scripts/lib/build-env.sh)" -m build --sdist --outdir "$partial" "$root" >/dev/null
(cd "$partial" && find . -type f ! -name SHA256SUMS | sed 's|^\./||' | sort | xargs sha256sum >SHA256SUMS)
rm -rf "$out"; mv "$partial" "$out"
echo "release $version in $out:"
(cd "$out" && ls -1 && echo && cat SHA256SUMS)
