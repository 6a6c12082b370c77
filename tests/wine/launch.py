"""Runs a script or module in the Windows CPython of scripts/wine-env.sh under Wine, as `python SCRIPT ARGS` or
`python -m MODULE ARGS` would on Windows, after wine_gaps.patch() (test code only: nothing of it is in the
product). The embeddable CPython does not put the script's folder on sys.path: done here.

    wine python.exe tests/wine/launch.py SCRIPT.py [ARGS...]
    wine python.exe tests/wine/launch.py -m pytest [ARGS...]
"""

import os
import runpy
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import wine_gaps  # noqa: E402

wine_gaps.patch()
if sys.argv[1] == "-m":
    sys.argv = sys.argv[2:]
    runpy.run_module(sys.argv[0], run_name="__main__", alter_sys=True)
else:
    sys.argv = sys.argv[1:]
    sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
    runpy.run_path(sys.argv[0], run_name="__main__")
