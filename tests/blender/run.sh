#!/usr/bin/env bash
# Runs one Blender test file in a fresh user profile (the add-on is installed there from its zip) with either
# Debian's Blender (BLENDER is an executable named blender*) or Blender as a Python module (BLENDER is the python
# of a virtual environment holding bpy, scripts/bpy-env.sh). Blender runs in background mode; with --gl on a
# virtual X display (OpenGL for EEVEE); with --ui in a window on one (for undo and panels; Debian's Blender only).
#   run.sh [--ui|--gl] BLENDER TEST.py ZIP SHARED_DIR [more test args]
set -euo pipefail
ui= gl=
if [[ $1 == --ui ]]; then ui=1; shift; fi
if [[ $1 == --gl ]]; then gl=1; shift; fi
blender=$1 test=$2 zip=$3 shared=$4
shift 4
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
export BLENDER_USER_SCRIPTS=$profile/scripts BLENDER_USER_CONFIG=$profile/config
export BLENDER_USER_EXTENSIONS=$profile/extensions BLENDER_USER_DATAFILES=$profile/datafiles
if [[ $(basename "$blender") != python* ]]; then
  # Debian's Blender embeds the system Python but takes its prefix from the first python3 on PATH: under a pyenv
  # shim (PyPI's cmake/ctest are one) that is pyenv's 3.11, which has no numpy. Give it a PATH without pyenv.
  PATH=$(tr ':' '\n' <<<"$PATH" | grep -v '/\.pyenv/' | paste -sd:)
  unset PYENV_VERSION PYENV_DIR PYENV_HOOK_PATH
  export PATH
fi
if [[ $(basename "$blender") == python* ]]; then
  command=("$blender" "$test")
  [[ -n $gl ]] && command=(xvfb-run -a -s "-screen 0 800x600x24" "${command[@]}")
elif [[ -n $ui ]]; then
  command=(xvfb-run -a -s "-screen 0 1920x1080x24" "$blender" --factory-startup -noaudio --enable-event-simulate --python "$test")
elif [[ -n $gl ]]; then
  command=(xvfb-run -a -s "-screen 0 800x600x24" "$blender" -b --factory-startup -noaudio --python-exit-code 1
           --python "$test")
else
  command=("$blender" -b --factory-startup -noaudio --python-exit-code 1 --python "$test")
fi
"${command[@]}" -- --zip "$zip" --shared "$shared" "$@" 2>&1 |
  grep -vE '^(PROGRESS \[|Fra:|Read prefs|Saved: |Info: Saved|Blender quit| Time: |ERROR \(bke.lib_id_delete\))|^[0-9:.]+ +render +\| Saved:'
