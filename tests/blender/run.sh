#!/usr/bin/env bash
# Runs one Blender background test file in a fresh user profile (the add-on is installed there from its zip).
#   run.sh BLENDER TEST.py ZIP SHARED_DIR
set -euo pipefail
blender=$1 test=$2 zip=$3 shared=$4
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
export BLENDER_USER_SCRIPTS=$profile/scripts BLENDER_USER_CONFIG=$profile/config
"$blender" -b --factory-startup -noaudio --python-exit-code 1 --python "$test" -- --zip "$zip" --shared "$shared" 2>&1 |
  grep -vE '^(Fra:|Read prefs|Saved: |Info: Saved|Blender quit| Time: |ERROR \(bke.lib_id_delete\))'
