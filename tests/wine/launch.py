"""Runs a script or module in the Windows CPython of scripts/wine-env.sh under Wine, as `python SCRIPT ARGS` or
`python -m MODULE ARGS` would on Windows (Wine's gaps are already filled: site imported the sitecustomize that
tests/wine/run.sh puts in). The embeddable CPython does not put the script's folder on sys.path: done here.

    wine python.exe tests/wine/launch.py [--env=NAME=VALUE ...] SCRIPT.py [ARGS...]
    wine python.exe tests/wine/launch.py [--env=NAME=VALUE ...] -m pytest [ARGS...]

--env sets a variable in the Windows process before anything runs (Blender reads its profile folders from
BLENDER_USER_*): the tests do not count on Wine passing the Linux environment on.
"""

import os
import runpy
import sys

while sys.argv[1].startswith("--env="):
    name, value = sys.argv.pop(1)[len("--env="):].split("=", 1)
    os.environ[name] = value
if sys.argv[1] == "-m":
    sys.argv = sys.argv[2:]
    runpy.run_module(sys.argv[0], run_name="__main__", alter_sys=True)
else:
    sys.argv = sys.argv[1:]
    sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
    runpy.run_path(sys.argv[0], run_name="__main__")
