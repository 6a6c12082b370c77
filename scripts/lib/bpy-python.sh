#!/usr/bin/env bash
# Prints the CPython minor version a pinned PyPI bpy is built for: 4.x and 5.0 for 3.11, 5.1 and later for 3.13.
#   scripts/lib/bpy-python.sh 4.5.15   -> 3.11
case "$1" in
  4.*|5.0.*) echo 3.11 ;;
  *)         echo 3.13 ;;
esac
