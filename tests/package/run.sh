#!/usr/bin/env bash
# `pip install probelights` as a user meets it: the wheel built for CPython 3.11 and 3.13 (scripts/wheel.sh),
# each installed into a fresh virtual environment with nothing else (pip brings numpy and openimageio), then
# test_package.py run there: the installed command and module against this build's, bit for bit.
#   tests/package/run.sh BUILD_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
for version in 3.11 3.13; do
  python=$(bash "$root/scripts/cpython.sh" "$version")
  wheel=$(bash "$root/scripts/wheel.sh" "$python" "$work/dist")
  echo "== $(basename "$wheel")"
  "$python" -m venv "$work/venv$version"
  "$work/venv$version/bin/pip" install -q --disable-pip-version-check "$wheel" pytest 2>&1 | grep -v '^WARNING: Location' || true
  (cd "$work" && PATH=$work/venv$version/bin:$PATH PROBELIGHTS_BUILD=$build PROBELIGHTS_WHEEL=$wheel \
     "$work/venv$version/bin/python" -m pytest -q -p no:cacheprovider "$here/test_package.py") || status=1
done
exit $status
