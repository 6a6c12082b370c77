#!/usr/bin/env bash
# Installs the Debian 12 packages probelights needs, only those that are missing. Run as root.
#   scripts/install-deps.sh          build + run (CLI, library, Python module)
#   scripts/install-deps.sh --test   also what the tests and the other platforms' builds need (GoogleTest, pytest,
#                                    Debian's oiiotool to write test images with a tool not ours, OpenEXR for the
#                                    decoder benchmark, Blender, Xvfb; MinGW-w64's gendef and dlltool for the Windows import
#                                    libraries, Wine to run the Windows builds, LLVM's tools to read macOS ones;
#                                    ccache, so a fresh clone's builds reuse earlier compiles; what CPython 3.13
#                                    is built with where there is none, scripts/cpython.sh)
set -euo pipefail
# OpenImageIO itself is PyPI's, assembled by scripts/oiio.sh (pip, python3-venv) with fmt's and Imath's headers.
packages=(cmake g++ make pkg-config libfmt-dev libimath-dev nlohmann-json3-dev python3-dev python3-numpy python3-pip
          python3-venv libbenchmark-dev fonts-dejavu-core)
if [[ "${1:-}" == "--test" ]]; then
  packages+=(libgtest-dev googletest python3-pytest openimageio-tools libopenexr-dev blender xvfb xauth libegl1
             libgl1-mesa-dri clang-format libssl-dev zlib1g-dev libffi-dev libbz2-dev liblzma-dev xz-utils
             mingw-w64-tools binutils-mingw-w64-x86-64 wine wine64 llvm-14 ccache)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  if [[ $(id -u) -ne 0 ]]; then SUDO=sudo; else SUDO=; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
