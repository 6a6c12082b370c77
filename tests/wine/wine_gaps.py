"""What Wine 8 (Debian 12) lacks that the Windows CPython, numpy or bpy use, filled in for the tests alone.
Nothing here runs on real Windows (patch() returns at once when ntdll has no wine_get_version).

- Python 3.13's `platform` asks WMI (the _wmi module), which needs propsys.VariantToString, a stub in Wine 8 that
  ends the process: _wmi is hidden, so `platform` falls back to sys.getwindowsversion().
- Wine 8's ucrtbase exports the C99 complex accessors (crealf, cimagf, creal, cimag, creall, cimagl) as stubs
  that end the process when called; numpy 2 calls crealf while it imports. Their bodies are replaced by the few
  instructions they are on Windows x64 (a float complex comes in RCX by value, a double complex by reference;
  long double is double there; the result goes back in XMM0).
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
    return patched
