#!/usr/bin/env bash
# Prints the Debian archive this machine installs from (the first Debian URI of its apt sources), so scripts that
# need one more suite or a source package take it from the machine's own configuration, never from the repository.
set -euo pipefail
uri=$(grep -rhoE '^(URIs:|deb) +[^ ]+' /etc/apt/sources.list /etc/apt/sources.list.d/ 2>/dev/null |
      awk '{print $2}' | grep -E '/debian/?$' | head -1 || true)
[[ -n $uri ]] || { echo "no Debian archive in /etc/apt/sources.list{,.d}" >&2; exit 1; }
echo "${uri%/}"
