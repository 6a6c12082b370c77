"""The `probelights` command of the Python package: the compiled command inside the package, run in this
process's place (its arguments, exit codes and signals its own)."""

import os
import sys


def main():
    exe = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "probelights")
    try:
        os.execv(exe, [exe, *sys.argv[1:]])
    except OSError as e:
        sys.stderr.write("probelights: the package's command cannot run (%s): reinstall probelights\n" % e.strerror)
        return 2


if __name__ == "__main__":
    sys.exit(main())
