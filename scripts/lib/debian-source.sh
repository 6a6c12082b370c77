#!/usr/bin/env bash
# Downloads a Debian source package of a given suite into a folder, through a private apt state (the machine's own
# archive, scripts/lib/debian-archive.sh; its lists and /etc/apt untouched), and prints the path of its upstream
# tarball (the .orig.tar.*).
#   scripts/lib/debian-source.sh PACKAGE SUITE FOLDER      e.g. python3.13 trixie /tmp/dl
set -euo pipefail
package=$1 suite=$2 dir=$(realpath -m "$3")
archive=$("$(dirname "$0")"/debian-archive.sh)
apt=$dir/apt-$suite
mkdir -p "$apt"/lists/partial "$apt"/cache/archives/partial
printf 'deb-src %s %s main\n' "$archive" "$suite" > "$apt/sources.list"
opts=(-o APT::Sandbox::User=root -o "Dir::Etc::SourceList=$apt/sources.list" -o Dir::Etc::SourceParts=/nonexistent
      -o "Dir::State::Lists=$apt/lists" -o "Dir::Cache=$apt/cache")
apt-get "${opts[@]}" update -qq >&2
(cd "$dir" && apt-get "${opts[@]}" source --download-only -qq "$package/$suite" >&2)
ls "$dir"/${package}_*.orig.tar.* | head -1
