#!/usr/bin/env bash
# Assembles (once) a pinned OpenImageIO in the cache and prints its prefix (lib/ and include/, as an install has).
# Why not Debian's OpenImageIO 2.4: it links 261 shared libraries (OpenVDB, GDAL, ...) and the loader binds ~153k
# symbols before main(), 0.27 s of a 1K bake's 0.32 s. PyPI's openimageio wheel links its image libraries
# (OpenEXR, libtiff, libpng, libjpeg-turbo, ...) statically and needs only libz and the C/C++ runtimes: its
# libOpenImageIO and libOpenImageIO_Util are taken from the wheel as they are. The wheel has no headers: they come
# from the same version's source distribution, with oiioversion.h filled in as OpenImageIO's CMake would and the
# fmt headers (Debian's libfmt-dev, OpenImageIO 3.2 takes fmt >= 9) copied where OpenImageIO's install puts them.
# Both downloads are pinned by hash and go through pip, with this machine's pip configuration.
# (docs/decisions.md: the start-up times measured for this choice.)
set -euo pipefail
version=3.2.2.0
wheel=openimageio-$version-cp311-cp311-manylinux_2_28_x86_64.whl
wheel_sha256=1133b6a6c04270398c419804e0d293b2bb3ce2d7607a17724cc45f385036b05b
sdist_sha256=d66c829016b4f092c443b7f7896f06d0ab6af02a103d635d1b0b841c14bfd7c1
sbc=0.11.6  # scikit-build-core: pip reads the source distribution's metadata with it before saving it
cache=${PROBELIGHTS_CACHE:-$HOME/.cache/probelights}
dir=$cache/openimageio-$version
if [[ -f $dir/.complete ]]; then echo "$dir"; exit 0; fi
[[ -f /usr/include/fmt/format.h ]] || { echo "oiio.sh: needs fmt's headers (apt install libfmt-dev)" >&2; exit 1; }
[[ -f /usr/include/Imath/ImathConfig.h ]] ||
  { echo "oiio.sh: needs Imath's headers (apt install libimath-dev)" >&2; exit 1; }
rm -rf "$dir"
work=$dir.partial
rm -rf "$work"; mkdir -p "$work/dl"
pip=(python3 -m pip -q --disable-pip-version-check)
echo "openimageio==$version --hash=sha256:$wheel_sha256" >"$work/wheel.txt"
"${pip[@]}" download --no-deps --only-binary=:all: --platform manylinux_2_28_x86_64 --python-version 3.11 \
  --implementation cp --require-hashes -r "$work/wheel.txt" -d "$work/dl" >&2
python3 -m venv "$work/venv"
"$work/venv/bin/pip" install -q --disable-pip-version-check "scikit-build-core==$sbc" >&2
echo "openimageio==$version --hash=sha256:$sdist_sha256" >"$work/sdist.txt"
"$work/venv/bin/pip" download -q --disable-pip-version-check --no-deps --no-binary=:all: --no-build-isolation \
  --require-hashes -r "$work/sdist.txt" -d "$work/dl" >&2

mkdir -p "$work/lib" "$work/include" "$work/src"
python3 - "$work" "$wheel" "$version" <<'EOF'
import re, sys, tarfile, zipfile, pathlib, shutil
work, wheel, version = pathlib.Path(sys.argv[1]), sys.argv[2], sys.argv[3]
with zipfile.ZipFile(work / "dl" / wheel) as z:
    for name in z.namelist():
        if re.fullmatch(r"OpenImageIO/lib/libOpenImageIO(_Util)?\.so\.[0-9.]+", name):
            target = work / "lib" / pathlib.Path(name).name
            target.write_bytes(z.read(name))
            target.chmod(0o755)
        elif name.endswith("LICENSE.md") or name.endswith("THIRD-PARTY.md"):
            (work / pathlib.Path(name).name).write_bytes(z.read(name))
with tarfile.open(work / "dl" / f"openimageio-{version}.tar.gz") as t:
    prefix = f"openimageio-{version}/src/include/OpenImageIO/"
    members = [m for m in t.getmembers() if m.name.startswith(prefix) and m.isfile()]
    for m in members:
        m.name = m.name[len(f"openimageio-{version}/src/include/"):]
    safe = {"filter": "data"} if hasattr(tarfile, "data_filter") else {}  # regular files under include/ only
    t.extractall(work / "include", members=members, **safe)
# oiioversion.h as OpenImageIO's CMake writes it (CMakeLists.txt: namespace OpenImageIO::vMAJ_MIN; the wheel is
# built as C++17 against header-only fmt).
major, minor, patch, tweak = version.split(".")
imath = re.search(r"#define IMATH_VERSION_STRING\s+\"(\d+)\.(\d+)",
                  pathlib.Path("/usr/include/Imath/ImathConfig.h").read_text())
values = {"PROJECT_VERSION_MAJOR": major, "PROJECT_VERSION_MINOR": minor, "PROJECT_VERSION_PATCH": patch,
          "PROJECT_VERSION_TWEAK": tweak, "PROJECT_VERSION_RELEASE_TYPE": "", "OIIO_USE_COMPILED_FMT_VALUE": "0",
          "PROJ_NAMESPACE": "OpenImageIO", "PROJ_VERSION_NAMESPACE": f"v{major}_{minor}",
          "Imath_VERSION_MAJOR": imath.group(1), "Imath_VERSION_MINOR": imath.group(2), "CMAKE_CXX_STANDARD": "17"}
switches = {"OIIO_TBB": 0}  # the wheel's build has no TBB (oiiotool --buildinfo: "TBB NONE")
header = work / "include/OpenImageIO/oiioversion.h.in"
text = re.sub(r"@(\w+)@", lambda m: values[m.group(1)], header.read_text())
text = re.sub(r"#cmakedefine01 (\w+)", lambda m: f"#define {m.group(1)} {switches[m.group(1)]}", text)
header.with_suffix("").write_text(text)
header.unlink()
shutil.copytree("/usr/include/fmt", work / "include/OpenImageIO/detail/fmt")
EOF
for lib in libOpenImageIO libOpenImageIO_Util; do  # the soname (e.g. libOpenImageIO.so.3.2.2) and the link name
  (cd "$work/lib" && ln -s "$(basename "$lib".so.*)" "$lib.so")
done
rm -rf "$work/dl" "$work/venv" "$work/src" "$work"/*.txt
touch "$work/.complete"
mv "$work" "$dir"
echo "$dir"
