#!/usr/bin/env bash
# Prints the Python of a cached virtual environment holding PyPA's `build` (pinned): the sdist (scripts/release.sh)
# and the wheel metadata that pyproject.toml's backend writes (scripts/wheel_platform.sh) come from it.
set -euo pipefail
env=${PROBELIGHTS_CACHE:-$HOME/.cache/probelights}/sdist-build-1.2.2
if [[ ! -f $env/.complete ]]; then
  rm -rf "$env"; python3 -m venv "$env" >&2
  "$env/bin/pip" install -q --disable-pip-version-check build==1.2.2 >&2
  touch "$env/.complete"
fi
echo "$env/bin/python"
