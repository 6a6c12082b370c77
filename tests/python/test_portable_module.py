"""The add-on's native modules load in any supported Blender: one per CPython ABI, linking nothing but libc, libm,
libpthread and the loader (a blender.org build has no OpenImageIO of Debian's, and maybe an older libstdc++), and
needing no newer glibc than measured; and a Blender without a matching module gets one line, not a traceback."""

import importlib
import os
import re
import shutil
import subprocess
import sys
import zipfile

import pytest

BUILD = os.environ.get("PROBELIGHTS_BUILD", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
ADDON_SOURCE = os.path.join(os.path.dirname(__file__), "..", "..", "addon", "probe_lights")
ALLOWED = {"libc.so.6", "libm.so.6", "libpthread.so.0", "ld-linux-x86-64.so.2"}
GLIBC_CEILING = (2, 35)  # measured with Debian 12's toolchain (README: "The oldest glibc it needs")


def zipped_modules():
    with zipfile.ZipFile(os.path.join(BUILD, "probe_lights.zip")) as z:
        names = z.namelist()
    assert "probe_lights/blender_manifest.toml" in names and "probe_lights/__init__.py" in names
    return [n for n in names if re.match(r"probe_lights/_probelights\.cpython-\d+-x86_64-linux-gnu\.so$", n)]


def test_the_zip_holds_a_module_for_each_blender_python():
    abis = sorted(re.search(r"cpython-(\d+)", n).group(1) for n in zipped_modules())
    assert abis == ["311", "313"], abis  # Blender 3.4 to 5.0; 5.1 and later


@pytest.mark.parametrize("name", ["311", "313"])
def test_needed_libraries_and_glibc(name):
    path = os.path.join(BUILD, "addon", "probe_lights", "_probelights.cpython-%s-x86_64-linux-gnu.so" % name)
    if not os.path.exists(path):
        pytest.skip("no module for cpython-%s in this build" % name)
    dynamic = subprocess.run(["readelf", "-d", "-W", path], check=True, capture_output=True, text=True).stdout
    needed = set(re.findall(r"\(NEEDED\)\s+Shared library: \[(.+?)\]", dynamic))
    assert needed and needed <= ALLOWED, needed - ALLOWED
    symbols = subprocess.run(["readelf", "-V", "-W", path], check=True, capture_output=True, text=True).stdout
    versions = {tuple(int(v) for v in m.split(".")) for m in re.findall(r"GLIBC_(\d+\.\d+(?:\.\d+)?)", symbols)}
    assert max(versions) <= GLIBC_CEILING, max(versions)


def test_a_blender_without_a_matching_module_gets_one_line(tmp_path):
    """native.py in a package whose only module is for another Python: the bake's error names both versions."""
    package = tmp_path / "fake_addon"
    package.mkdir()
    for name in ("native.py", "errors.py"):
        shutil.copy(os.path.join(ADDON_SOURCE, name), package / name)
    (package / "__init__.py").write_text("")
    (package / "_probelights.cpython-399-x86_64-linux-gnu.so").write_bytes(b"")
    sys.path.insert(0, str(tmp_path))
    try:
        native = importlib.import_module("fake_addon.native")
        errors = importlib.import_module("fake_addon.errors")
        assert native.built_for() == ["3.99"]
        with pytest.raises(errors.ProbeError) as e:
            native.bake(None)
        message = str(e.value)
        assert "\n" not in message
        assert message == "Probe Lights needs Blender with Python 3.99; this Blender runs Python %d.%d" % sys.version_info[:2]
        assert native.unavailable() == message  # the panel's line; the failed import is not retried
    finally:
        sys.path.remove(str(tmp_path))
