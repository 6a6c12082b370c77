#!/usr/bin/env bash
# Runs a Python script (or -m MODULE) under Wine in a Windows CPython of scripts/wine-env.sh:
#   tests/wine/run.sh ENV_DIR SCRIPT.py [ARGS...]      ENV_DIR as printed by scripts/wine-env.sh
# Paths given to the script may be Linux paths: Wine maps / to drive Z:, and a path that starts with / is read on
# the current drive, which is Z: here.
set -euo pipefail
env=$1; shift
export WINEPREFIX=$env/prefix WINEDEBUG=-all WINEDLLOVERRIDES="mscoree,mshtml=;winemenubuilder.exe=d"
export PYTHONIOENCODING=utf-8 PYTHONUNBUFFERED=1
here=$(cd "$(dirname "$0")" && pwd)
# Wine's console python.exe cannot write to a plain file: its output goes through a pipe; CRs are dropped.
wine "$env/python/python.exe" "$here/launch.py" "$@" </dev/null 2>&1 | tr -d '\r'
exit "${PIPESTATUS[0]}"
