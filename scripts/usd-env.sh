#!/usr/bin/env bash
# Creates (once) and prints the path of a virtual environment holding PyPI's usd-core (OpenUSD's Python
# module, pinned), for the tests that read back the USD files probelights writes (tests/python/test_usd.py).
# On the system's Python with its packages (pytest, numpy) visible, outside the repository like the bpy
# environments (PROBELIGHTS_CACHE, default ~/.cache/probelights).
set -euo pipefail
version=$(cat "$(dirname "$0")/../tests/usd-core-version")
cache=${PROBELIGHTS_CACHE:-$HOME/.cache/probelights}
env=$cache/usd-core-$version
if [[ -x $env/bin/python && -f $env/.complete ]]; then echo "$env"; exit 0; fi
rm -rf "$env"; mkdir -p "$cache"
python3 -m venv --system-site-packages "$env" >&2
"$env/bin/python" -m pip install -q --disable-pip-version-check "usd-core==$version" >&2
"$env/bin/python" -c "from pxr import Usd; print('usd-core', Usd.GetVersion(), file=__import__('sys').stderr)"
touch "$env/.complete"
echo "$env"
