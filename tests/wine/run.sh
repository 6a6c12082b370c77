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
# Every Python process of the environment patches Wine's gaps (Blender's extension installer runs one of its
# own): site imports sitecustomize, which this run puts in (replaced whole: runs may share the environment).
for file in wine_gaps.py sitecustomize.py; do
  cp "$here/$file" "$env/site-packages/.$file.$$" && mv -f "$env/site-packages/.$file.$$" "$env/site-packages/$file"
done
# Wine's console python.exe cannot write to a plain file: its output goes through a pipe; CRs are dropped.
wine "$env/python/python.exe" "$here/launch.py" "$@" </dev/null 2>&1 | tr -d '\r'
exit "${PIPESTATUS[0]}"
