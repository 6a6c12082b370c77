"""What Wine 8 (Debian 12) lacks that the Windows CPython, numpy or bpy use, filled in for the tests alone.
Nothing here runs on real Windows (patch() returns at once when ntdll has no wine_get_version).

- Python 3.13's `platform` asks WMI (the _wmi module), which needs propsys.VariantToString, a stub in Wine 8 that
  ends the process: _wmi is hidden, so `platform` falls back to sys.getwindowsversion().
- Wine 8's ucrtbase exports the C99 complex accessors (crealf, cimagf, creal, cimag, creall, cimagl) as stubs
  that end the process when called; numpy 2 calls crealf while it imports. Their bodies are replaced by the few
  instructions they are on Windows x64 (a float complex comes in RCX by value, a double complex by reference;
  long double is double there; the result goes back in XMM0).
- Blender 5.x maps image files through kernelbase's VirtualAlloc2 and MapViewOfFile3 with placeholders
  (MEM_RESERVE_PLACEHOLDER) when GetProcAddress finds them, which Wine 8 exports but does not support: every
  image load fails ("couldn't get mapping"). The export's name is changed in kernelbase's export table in memory
  (MapViewOfFile3 -> MapViewOfFile0, which keeps the table sorted), so Blender takes its own fallback, the plain
  CreateFileMapping and MapViewOfFile that Blender used before and Wine supports.
- Python 3.13's shutil copies files with kernel32's CopyFile2 where _winapi has it; Wine 8 does not implement it
  and ends the process (Blender's extension installer copies with shutil): _winapi's CopyFile2 is removed, so
  shutil copies as it did before 3.13, by reading and writing.
"""

import ctypes
import sys

ACCESSORS = {
    "crealf": "66 0F 6E C1 C3",              # movd xmm0, ecx; ret
    "cimagf": "48 C1 E9 20 66 0F 6E C1 C3",  # shr rcx, 32; movd xmm0, ecx; ret
    "creal": "F2 0F 10 01 C3",               # movsd xmm0, [rcx]; ret
    "cimag": "F2 0F 10 41 08 C3",            # movsd xmm0, [rcx + 8]; ret
    "creall": "F2 0F 10 01 C3",
    "cimagl": "F2 0F 10 41 08 C3",
}


def under_wine():
    return sys.platform == "win32" and hasattr(ctypes.WinDLL("ntdll"), "wine_get_version")


def rename_export(kernel, dll, name, new_name):
    """Renames one export of a loaded DLL in its PE export table (the names are sorted: keep the order)."""
    assert len(new_name) == len(name)
    kernel.LoadLibraryW.restype = ctypes.c_void_p
    base = kernel.LoadLibraryW(dll)
    if not base:
        return False
    u32 = lambda address: ctypes.c_uint32.from_address(address).value  # noqa: E731
    optional = base + u32(base + 0x3C) + 24          # PE signature (4) + COFF header (20)
    if ctypes.c_uint16.from_address(optional).value != 0x20B:
        return False                                 # not PE32+
    exports = base + u32(optional + 112)             # DataDirectory[0] of a PE32+ optional header
    count, names = u32(exports + 24), base + u32(exports + 32)
    for i in range(count):
        address = base + u32(names + 4 * i)
        if ctypes.string_at(address) == name:
            old = ctypes.c_uint32()
            if not kernel.VirtualProtect(address, len(name), 0x04, ctypes.byref(old)):  # PAGE_READWRITE
                return False
            ctypes.memmove(address, new_name, len(new_name))
            kernel.VirtualProtect(address, len(name), old.value, ctypes.byref(old))
            return True
    return False


def patch():
    if not under_wine():
        return []
    sys.modules.setdefault("_wmi", None)
    kernel = ctypes.WinDLL("kernel32", use_last_error=True)
    kernel.GetModuleHandleW.restype = ctypes.c_void_p
    kernel.GetProcAddress.restype = ctypes.c_void_p
    kernel.GetProcAddress.argtypes = [ctypes.c_void_p, ctypes.c_char_p]
    kernel.VirtualProtect.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_uint32,
                                      ctypes.POINTER(ctypes.c_uint32)]
    kernel.FlushInstructionCache.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t]
    ctypes.CDLL("ucrtbase")
    ucrt = kernel.GetModuleHandleW("ucrtbase.dll")
    patched = []
    for name, hexcode in ACCESSORS.items():
        code = bytes.fromhex(hexcode)
        address = kernel.GetProcAddress(ucrt, name.encode())
        old = ctypes.c_uint32()
        if not address or not kernel.VirtualProtect(address, len(code), 0x40, ctypes.byref(old)):
            continue
        ctypes.memmove(address, code, len(code))
        kernel.VirtualProtect(address, len(code), old.value, ctypes.byref(old))
        kernel.FlushInstructionCache(kernel.GetCurrentProcess(), address, len(code))
        patched.append(name)
    if rename_export(kernel, "kernelbase.dll", b"MapViewOfFile3", b"MapViewOfFile0"):
        patched.append("MapViewOfFile3")
    import _winapi
    if hasattr(_winapi, "CopyFile2"):  # shutil copies with it when it is there (3.13)
        del _winapi.CopyFile2
        patched.append("CopyFile2")
    return patched
