#!/usr/bin/env bash
# Loads the add-on's modules on an older glibc: debootstraps Debian 11 (glibc 2.31) once into the cache and runs
# `ldd -r` there. Every C library and pthread symbol must resolve; what stays undefined is the Python API that
# Blender's Python provides. A control library built here normally (needs GLIBC_2.34) must fail. Run as root.
#   scripts/check_old_glibc.sh [build/addon/probe_lights]
set -euo pipefail
cd "$(dirname "$0")/.."
modules=${1:-build/addon/probe_lights}
root=${PROBELIGHTS_CACHE:-$HOME/.cache/probelights}/debian11-root
if [[ ! -f $root/.complete ]]; then
  command -v debootstrap >/dev/null || apt-get install -y -qq debootstrap >/dev/null
  rm -rf "$root"; debootstrap --variant=minbase bullseye "$root" "$(scripts/lib/debian-archive.sh)" >/dev/null
  touch "$root/.complete"
fi
echo "glibc there: $(chroot "$root" ldd --version | head -1)"
printf '#include <pthread.h>\nstatic void* f(void* a){return a;}\nint go(void){pthread_t t; pthread_create(&t,0,f,0); return pthread_join(t,0);}\n' |
  gcc -shared -fPIC -x c -o "$root/tmp/control.so" -
if chroot "$root" ldd -r /tmp/control.so 2>&1 | grep -q "GLIBC_2.34' not found"; then
  echo "control (pthread_create@GLIBC_2.34): does not load, as expected"
else
  echo "control loaded: this root does not test an old glibc" >&2; exit 1
fi
status=0
for module in "$modules"/_probelights.cpython-*.so; do
  cp "$module" "$root/tmp/"
  report=$(chroot "$root" ldd -r "/tmp/$(basename "$module")" 2>&1 || true)
  missing=$(grep -E "not found|undefined symbol" <<<"$report" | grep -vE "undefined symbol: _?Py" || true)
  python_api=$(grep -c "undefined symbol: _\?Py" <<<"$report" || true)
  if [[ -n $missing ]]; then
    echo "$(basename "$module"): does NOT load:"; echo "$missing"; status=1
  else
    echo "$(basename "$module"): every C library symbol resolves ($python_api Python API symbols left to the host)"
  fi
done
exit $status
