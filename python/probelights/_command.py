"""The `probelights` command of the Python package: the command line compiled into the package's module, run in
this process as the program would run (its arguments, output, exit codes and signals its own)."""

import os
import signal
import sys


def main():
    # A program's signals: Ctrl-C stops it (the command removes a half-written file first), and output to a
    # closed pipe (`probelights ... | head`) ends it quietly. Python would raise KeyboardInterrupt / ignore SIGPIPE.
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    if hasattr(signal, "SIGPIPE"):
        signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    try:
        from . import _probelights
    except ImportError as e:
        sys.stderr.write("probelights: the package's module cannot load (%s): reinstall probelights\n" % e)
        return 2
    return _probelights._command([os.fsencode(a) for a in sys.argv[1:]])


if __name__ == "__main__":
    sys.exit(main())
