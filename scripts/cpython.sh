#!/usr/bin/env bash
# Prints a CPython of the given minor version (default 3.13): pyenv's or the system's where this machine has one,
# else one built once into the cache from Debian's source package of it. Blender 5.1 and later run on 3.13, which
# Debian 12 does not have: the bpy environments of those Blenders, the Windows ones' pip, and the add-on's cp313
# module (its headers) need one.
#   scripts/cpython.sh 3.13     -> e.g. ~/.cache/probelights/cpython-3.13/bin/python3.13
set -euo pipefail
minor=${1:-3.13}
for candidate in "${PYENV_ROOT:-$HOME/.pyenv}"/versions/$minor.*/bin/python$minor /usr/bin/python$minor \
                 /usr/local/bin/python$minor; do
  [[ -x $candidate ]] && { echo "$candidate"; exit 0; }
done
declare -A suite=([3.13]=trixie)
[[ -n ${suite[$minor]:-} ]] || { echo "cpython.sh: no CPython $minor here and no Debian source of it known" >&2; exit 3; }
cache=${PROBELIGHTS_CACHE:-$HOME/.cache/probelights}
dir=$cache/cpython-$minor
if [[ -f $dir/.complete ]]; then echo "$dir/bin/python$minor"; exit 0; fi
for header in openssl/ssl.h zlib.h ffi.h bzlib.h lzma.h; do
  [[ -f /usr/include/$header || -f /usr/include/x86_64-linux-gnu/$header ]] ||
    { echo "cpython.sh: $header missing: scripts/install-deps.sh --test installs it" >&2; exit 3; }
done
echo "building CPython $minor from Debian's source package (once, a few minutes) into $dir" >&2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tarball=$("$(dirname "$0")"/lib/debian-source.sh "python$minor" "${suite[$minor]}" "$work")
tar xf "$tarball" -C "$work"
src=$(ls -d "$work"/Python-*/ | head -1)
rm -rf "$dir"
(cd "$src" && ./configure -q --prefix="$dir" --with-ensurepip=install >&2 && make -s -j"$(nproc)" >/dev/null &&
  make -s install >/dev/null)
"$dir/bin/python$minor" -c "import ssl, zlib, ctypes, bz2, lzma" ||
  { echo "cpython.sh: the CPython built lacks a module pip or bpy need" >&2; exit 1; }
touch "$dir/.complete"
echo "$dir/bin/python$minor"
