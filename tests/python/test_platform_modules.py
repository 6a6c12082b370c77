"""The add-on's zips for every Blender platform, read as the platform's loader would: each zip names its one
platform and holds a module for CPython 3.11 and 3.13 under that platform's extension suffix; a Windows module
imports KERNEL32, the UCRT and python3XY.dll and nothing else, a macOS module libSystem alone, for macOS 11 on, the
arm64 one with a code signature (arm64 loads nothing unsigned); each exports the module's init function alone. And the macOS
pyconfig.h derived by scripts/macos_pyconfig.py agrees with the target's compiler on every size and alignment.
The Python package's Windows and macOS wheels (scripts/wheel_platform.sh, into PROBELIGHTS_PLATFORM_WHEELS) are
read the same way: their modules need no more than the add-on's, and each wheel carries the package and its tag.
The Windows modules also run, under Wine (tests/wine/); the macOS ones cannot run here."""

import os
import re
import subprocess
import tempfile
import zipfile

import pytest

BUILD = os.environ.get("PROBELIGHTS_BUILD", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
CROSS = os.environ.get("PROBELIGHTS_CROSS", "")
HERE = os.path.dirname(os.path.abspath(__file__))
VERSION = re.search(r'^version = "(.+)"', open(os.path.join(HERE, "..", "..", "addon", "probe_lights",
                                                            "blender_manifest.toml")).read(), re.M).group(1)
MODULES = {
    "linux-x64": ["_probelights.cpython-311-x86_64-linux-gnu.so", "_probelights.cpython-313-x86_64-linux-gnu.so"],
    "windows-x64": ["_probelights.cp311-win_amd64.pyd", "_probelights.cp313-win_amd64.pyd"],
    "macos-arm64": ["_probelights.cpython-311-darwin.so", "_probelights.cpython-313-darwin.so"],
    "macos-x64": ["_probelights.cpython-311-darwin.so", "_probelights.cpython-313-darwin.so"],
}


def zip_path(platform):
    return os.path.join(BUILD, "probe_lights-%s-%s.zip" % (VERSION, platform.replace("-", "_")))


WHEELS = os.environ.get("PROBELIGHTS_PLATFORM_WHEELS")  # the package_platform_wheels test's (tests/CMakeLists.txt)
WHEEL_TAGS = {"windows-x64": "win_amd64", "macos-arm64": "macosx_11_0_arm64", "macos-x64": "macosx_11_0_x86_64"}


def wheel_path(platform, abi):
    return os.path.join(WHEELS, "probelights-%s-cp%s-cp%s-%s.whl" % (VERSION, abi, abi, WHEEL_TAGS[platform]))


def module_bytes(platform, name, source="zip"):
    abi = re.search(r"cp(?:ython-)?(\d+)", name).group(1)
    if source == "wheel" and not WHEELS:
        pytest.skip("no platform wheels (PROBELIGHTS_PLATFORM_WHEELS)")
    path = zip_path(platform) if source == "zip" else wheel_path(platform, abi)
    if not os.path.exists(path):
        pytest.skip("%s not built (%s)" % (os.path.basename(path), "PROBELIGHTS_PLATFORMS" if source == "zip"
                                           else "scripts/wheel_platform.sh"))
    with zipfile.ZipFile(path) as z:
        return z.read(("probe_lights/" if source == "zip" else "probelights/") + name)


@pytest.mark.parametrize("platform", sorted(WHEEL_TAGS))
@pytest.mark.parametrize("abi", ["311", "313"])
def test_each_wheel_holds_the_package_its_module_and_its_tag(platform, abi):
    if not WHEELS:
        pytest.skip("no platform wheels (PROBELIGHTS_PLATFORM_WHEELS)")
    path = wheel_path(platform, abi)
    if not os.path.exists(path):
        pytest.skip("%s not built (scripts/wheel_platform.sh)" % os.path.basename(path))
    with zipfile.ZipFile(path) as z:
        names = set(z.namelist())
        info = "probelights-%s.dist-info/" % VERSION
        wheel = z.read(info + "WHEEL").decode()
        record = z.read(info + "RECORD").decode()
        metadata = z.read(info + "METADATA").decode()
    module = MODULES[platform][["311", "313"].index(abi)]
    assert {"probelights/__init__.py", "probelights/__init__.pyi", "probelights/_command.py",
            "probelights/" + module, info + "entry_points.txt", info + "licenses/LICENSE"} <= names
    assert "Tag: cp%s-cp%s-%s" % (abi, abi, WHEEL_TAGS[platform]) in wheel.splitlines()
    assert {line.split(",")[0] for line in record.splitlines()} == names
    assert "Requires-Dist: openimageio==" in metadata and "Version: " + VERSION in metadata


def run(*command):
    return subprocess.run(command, check=True, capture_output=True, text=True).stdout


@pytest.mark.parametrize("platform", sorted(MODULES))
def test_each_zip_names_its_platform_and_holds_its_modules(platform):
    path = zip_path(platform)
    if not os.path.exists(path):
        pytest.skip("%s not built (PROBELIGHTS_PLATFORMS)" % os.path.basename(path))
    with zipfile.ZipFile(path) as z:
        names = z.namelist()
        manifest = z.read("probe_lights/blender_manifest.toml").decode()
    assert re.findall(r"^platforms = (.*)$", manifest, re.M) == ['["%s"]' % platform]
    native = sorted(n.split("/")[-1] for n in names if re.search(r"\.(so|pyd|dylib|dll)$", n))
    assert native == MODULES[platform]
    assert "probe_lights/__init__.py" in names and not any("__pycache__" in n for n in names)


@pytest.mark.parametrize("source", ["zip", "wheel"])
@pytest.mark.parametrize("abi", ["311", "313"])
def test_windows_modules_import_the_system_the_ucrt_and_python_alone(abi, source, tmp_path):
    name = "_probelights.cp%s-win_amd64.pyd" % abi
    path = tmp_path / name
    path.write_bytes(module_bytes("windows-x64", name, source))
    dump = run("x86_64-w64-mingw32-objdump", "-p", str(path))
    assert "file format pei-x86-64" in run("x86_64-w64-mingw32-objdump", "-f", str(path))
    dlls = set(re.findall(r"DLL Name: (\S+)", dump))
    other = {d for d in dlls if not re.fullmatch(r"api-ms-win-crt-[a-z]+-l1-1-0\.dll", d)}
    assert other == {"KERNEL32.dll", "python%s.dll" % abi}, other
    exports = re.findall(r"\[\s*\d+\] (\S+)", dump.split("[Ordinal/Name Pointer] Table")[1].split("\n\n")[0])
    assert exports == ["PyInit__probelights"]


@pytest.mark.parametrize("source", ["zip", "wheel"])
@pytest.mark.parametrize("platform, cpu", [("macos-arm64", "ARM64"), ("macos-x64", "X86_64")])
@pytest.mark.parametrize("abi", ["311", "313"])
def test_macos_modules_need_libsystem_alone_and_are_signed(platform, cpu, abi, source, tmp_path):
    name = "_probelights.cpython-%s-darwin.so" % abi
    path = tmp_path / name
    path.write_bytes(module_bytes(platform, name, source))
    headers = run("llvm-objdump-14", "--macho", "--private-headers", str(path))
    assert re.search(r"\bMH_MAGIC_64\s+%s\b" % cpu, headers), headers[:400]
    used = [u.split()[0] for u in run("llvm-objdump-14", "--macho", "--dylibs-used", str(path)).splitlines()[1:]]
    assert [u for u in used if u != name] == ["/usr/lib/libSystem.B.dylib"], used  # less its own LC_ID_DYLIB
    build = headers.split("cmd LC_BUILD_VERSION")[1]
    assert re.search(r"platform (1|macos)\b", build) and re.search(r"minos 11\.0\b", build), build[:200]
    # arm64 Macs load no unsigned code (zig's linker signs ad hoc); Intel Macs do, as they load PyPI's x86_64
    # wheels that Blender's extensions bundle, and zig 0.14 signs arm64 alone.
    assert ("LC_CODE_SIGNATURE" in headers) == (cpu == "ARM64")
    exported = run("llvm-nm-14", "--extern-only", "--defined-only", str(path)).split()
    names = [s for s in exported if not re.fullmatch(r"[0-9a-f]+|[A-Z]", s)]
    # (the linker's own two: every dylib has them)
    assert sorted(names) == ["_PyInit__probelights", "___dso_handle", "__mh_dylib_header"], names
    undefined = run("llvm-nm-14", "--undefined-only", str(path)).split()
    python = [s for s in undefined if re.match(r"__?Py|_PyExc_", s)]
    assert python, "the Python API is left to the host Blender (-undefined dynamic_lookup)"


# What each pyconfig.h size or alignment macro measures.
MEASURES = {
    "SIZEOF_SHORT": "sizeof(short)", "SIZEOF_INT": "sizeof(int)", "SIZEOF_LONG": "sizeof(long)",
    "SIZEOF_LONG_LONG": "sizeof(long long)", "SIZEOF_FLOAT": "sizeof(float)", "SIZEOF_DOUBLE": "sizeof(double)",
    "SIZEOF_LONG_DOUBLE": "sizeof(long double)", "SIZEOF_VOID_P": "sizeof(void*)",
    "SIZEOF_SIZE_T": "sizeof(size_t)", "SIZEOF_WCHAR_T": "sizeof(wchar_t)", "SIZEOF_UINTPTR_T": "sizeof(uintptr_t)",
    "SIZEOF_PTHREAD_KEY_T": "sizeof(pthread_key_t)", "SIZEOF_FPOS_T": "sizeof(fpos_t)",
    "SIZEOF_PID_T": "sizeof(pid_t)", "SIZEOF_TIME_T": "sizeof(time_t)", "SIZEOF_OFF_T": "sizeof(off_t)",
    "SIZEOF_PTHREAD_T": "sizeof(pthread_t)", "SIZEOF__BOOL": "sizeof(bool)", "ALIGNOF_LONG": "alignof(long)",
    "ALIGNOF_SIZE_T": "alignof(size_t)", "ALIGNOF_MAX_ALIGN_T": "alignof(max_align_t)",
}


@pytest.mark.parametrize("target", ["aarch64-macos.11.0", "x86_64-macos.11.0"])
@pytest.mark.parametrize("abi", ["311", "313"])
def test_the_derived_macos_pyconfig_agrees_with_the_compiler(target, abi):
    if not CROSS:
        pytest.skip("no cross toolchain (PROBELIGHTS_CROSS: scripts/cross-toolchain.sh)")
    headers = os.path.join(CROSS, "python", "cp" + abi)
    pyconfig = open(os.path.join(headers, "macos", "pyconfig.h")).read()
    macros = sorted(set(re.findall(r"^#define ((?:SIZEOF|ALIGNOF)_\w+)", pyconfig, re.M)))
    assert set(macros) <= set(MEASURES), set(macros) - set(MEASURES)
    checks = "".join('static_assert(%s == %s, "%s");\n' % (m, MEASURES[m], m) for m in macros)
    x64 = target.startswith("x86_64")
    source = ("#include <Python.h>\n#include <cstddef>\n#include <cstdint>\n#include <cstdio>\n#include <pthread.h>\n"
              "#include <sys/types.h>\n#include <wchar.h>\n" + checks +
              "#if %sdefined(HAVE_GCC_ASM_FOR_X64)\n#error HAVE_GCC_ASM_FOR_X64 on the wrong architecture\n#endif\n"
              % ("!" if x64 else ""))
    with tempfile.TemporaryDirectory() as folder:
        with open(os.path.join(folder, "check.cpp"), "w") as f:
            f.write(source)
        try:  # compiled, not only parsed: zig c++ wants an object to come out
            subprocess.run([os.path.join(CROSS, "bin", target + "-c++"), "-std=c++20", "-c", "-I",
                            os.path.join(headers, "macos"), "-I", os.path.join(headers, "Include"), f.name,
                            "-o", os.path.join(folder, "check.o")], check=True, capture_output=True, text=True)
        except subprocess.CalledProcessError as e:
            pytest.fail(e.stderr[-2000:])
    assert len(macros) >= 20
