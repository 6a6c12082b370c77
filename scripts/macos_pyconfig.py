"""Derives a pyconfig.h for building extension modules for macOS (arm64 and x86_64) from a Linux x86-64 one of the
same CPython version, written to standard output:

    python3 scripts/macos_pyconfig.py LINUX_PYCONFIG_H > macos/pyconfig.h

No macOS CPython can be had here (PyPI has no macOS headers; Blender's macOS Python is inside its app). An
extension module sees pyconfig.h only through Python.h's headers: type sizes and alignments (object layouts,
PyLong digits, hashing), a few feature switches, and the platform's feature-test macros. So:
- every SIZEOF_* / ALIGNOF_* whose type the compiler describes becomes the compiler's own predefined macro
  (__SIZEOF_LONG_DOUBLE__ ...): right on each architecture by construction, not by a table;
- the rest, which POSIX leaves to the platform (pthread_key_t, fpos_t, max_align_t), get Darwin's values per
  architecture;
- Linux's feature-test macros (_GNU_SOURCE, _POSIX_C_SOURCE ...: on Darwin they hide the BSD interfaces) and
  the HAVE_* of Linux-only headers and calls are dropped; _DARWIN_C_SOURCE is defined, as CPython's configure
  does on Darwin.
tests/python/test_platform_modules.py compiles static_asserts of every size and alignment macro against sizeof and
alignof on both macOS targets.
"""

import re
import sys

# Macros whose value the compiler predefines (clang and GCC: __SIZEOF_<T>__).
FROM_COMPILER = {
    "SIZEOF_SHORT": "__SIZEOF_SHORT__", "SIZEOF_INT": "__SIZEOF_INT__", "SIZEOF_LONG": "__SIZEOF_LONG__",
    "SIZEOF_LONG_LONG": "__SIZEOF_LONG_LONG__", "SIZEOF_FLOAT": "__SIZEOF_FLOAT__",
    "SIZEOF_DOUBLE": "__SIZEOF_DOUBLE__", "SIZEOF_LONG_DOUBLE": "__SIZEOF_LONG_DOUBLE__",
    "SIZEOF_VOID_P": "__SIZEOF_POINTER__", "SIZEOF_SIZE_T": "__SIZEOF_SIZE_T__",
    "SIZEOF_WCHAR_T": "__SIZEOF_WCHAR_T__", "SIZEOF_UINTPTR_T": "__SIZEOF_POINTER__",
    "ALIGNOF_LONG": "__SIZEOF_LONG__", "ALIGNOF_SIZE_T": "__SIZEOF_SIZE_T__",
}
# Darwin's own, the same on arm64 and x86_64 (<sys/_types.h>: pthread_key_t is unsigned long, fpos_t is off_t,
# pid_t int, time_t long, off_t long long, pthread_t a pointer).
DARWIN = {
    "SIZEOF_PTHREAD_KEY_T": "8", "SIZEOF_FPOS_T": "8", "SIZEOF_PID_T": "4", "SIZEOF_TIME_T": "8",
    "SIZEOF_OFF_T": "8", "SIZEOF_PTHREAD_T": "8", "SIZEOF__BOOL": "1",
}
# Linux's feature-test macros, Linux-only headers and calls, and x86-only inline assembly (set again below for
# x86_64 alone).
DROP = re.compile(r"^(_GNU_SOURCE|_POSIX_C_SOURCE|_XOPEN_SOURCE|_XOPEN_SOURCE_EXTENDED|_DARWIN_C_SOURCE|"
                  r"_NETBSD_SOURCE|__BSD_VISIBLE|ALIGNOF_MAX_ALIGN_T|HAVE_GCC_ASM_FOR_X64|HAVE_GCC_ASM_FOR_X87|"
                  r"HAVE_LINUX_\w+|HAVE_SYS_EPOLL_H|HAVE_EPOLL\w*|HAVE_EVENTFD|HAVE_SYS_EVENTFD_H|"
                  r"HAVE_MEMFD_CREATE|HAVE_PRLIMIT|HAVE_SCHED_SETAFFINITY|HAVE_SYS_SYSMACROS_H|"
                  r"MAJOR_IN_SYSMACROS|PY_HAVE_PERF_TRAMPOLINE|HAVE_PIDFD_\w+|HAVE_SPLICE|HAVE_COPY_FILE_RANGE)$")
DEFINE = re.compile(r"^(\s*#\s*define\s+)(\w+)(\s.*)?$")


def derive(lines):
    out, seen = [], set()
    for line in lines:
        m = DEFINE.match(line)
        if not m:
            out.append(line)
            continue
        name = m.group(2)
        if DROP.match(name):
            continue
        if name in FROM_COMPILER:
            line, seen = "%s%s %s\n" % (m.group(1), name, FROM_COMPILER[name]), seen | {name}
        elif name in DARWIN:
            line, seen = "%s%s %s\n" % (m.group(1), name, DARWIN[name]), seen | {name}
        elif re.match(r"(SIZEOF|ALIGNOF)_", name):
            raise SystemExit("macos_pyconfig.py: no macOS value known for %s: add it" % name)
        out.append(line)
    # The header's own include guard ends the file: the macOS block goes before its last #endif.
    last = max(i for i, l in enumerate(out) if l.strip().startswith("#endif"))
    darwin = ["\n/* macOS (scripts/macos_pyconfig.py) */\n",
              "#ifndef __APPLE__\n#error \"this pyconfig.h is for macOS targets only\"\n#endif\n",
              "#define _DARWIN_C_SOURCE 1\n",
              "#if defined(__x86_64__)\n#define ALIGNOF_MAX_ALIGN_T 16\n#define HAVE_GCC_ASM_FOR_X64 1\n"
              "#define HAVE_GCC_ASM_FOR_X87 1\n#else\n#define ALIGNOF_MAX_ALIGN_T 8\n#endif\n"]
    return "".join(out[:last] + darwin + out[last:])


if __name__ == "__main__":
    with open(sys.argv[1]) as f:
        sys.stdout.write(derive(f.readlines()))
