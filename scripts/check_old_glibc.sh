#!/usr/bin/env bash
# Loads our Linux binaries on an older glibc, in a Debian 11 root (glibc 2.31) debootstrapped once into the cache.
# Run as root.
#   scripts/check_old_glibc.sh [build/addon/probe_lights]
#       the add-on's modules: `ldd -r` there. Every C library and pthread symbol must resolve; what stays undefined
#       is the Python API that Blender's Python provides. A control library built here normally (needs
#       GLIBC_2.34) must fail.
#   scripts/check_old_glibc.sh --wheel build/release/probelights-*-cp311-*.whl [build/bin/probelights]
#       the Python package as `pip install` there gives it (a CPython 3.11 built in the root once from Debian's
#       source package of it): the command and the module bake the bundled probe; the lights equal this machine's
#       build/bin's bit for bit, the refit's colours to 1e-9 and the evaluator's errors to 1e-12 (relative: another
#       glibc's libm, whose last bits the refit's solve carries further).
set -euo pipefail
cd "$(dirname "$0")/.."
root=${PROBELIGHTS_CACHE:-$HOME/.cache/probelights}/debian11-root
if [[ ! -f $root/.complete ]]; then
  command -v debootstrap >/dev/null || apt-get install -y -qq debootstrap >/dev/null
  rm -rf "$root"; debootstrap --variant=minbase bullseye "$root" "$(scripts/lib/debian-archive.sh)" >/dev/null
  touch "$root/.complete"
fi
echo "glibc there: $(chroot "$root" ldd --version | head -1)"
in_root() { chroot "$root" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root "$@"; }

if [[ ${1:-} == --wheel ]]; then
  wheel=$2 cli=${3:-build/bin/probelights}
  if [[ ! -f $root/opt/py311/.complete ]]; then
    echo "building CPython 3.11 in the root (once, a few minutes)"
    cp /etc/resolv.conf "$root/etc/resolv.conf"
    in_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq gcc make libssl-dev zlib1g-dev libffi-dev \
      ca-certificates >/dev/null
    work=$(mktemp -d)
    tarball=$(scripts/lib/debian-source.sh python3.11 bookworm "$work")
    rm -rf "$root/build"; mkdir -p "$root/build"; tar xf "$tarball" -C "$root/build"; rm -rf "$work"
    in_root sh -c "cd /build/Python-* && ./configure -q --prefix=/opt/py311 --with-ensurepip=install >/dev/null &&
                   make -s -j$(nproc) >/dev/null 2>&1 && make -s install >/dev/null 2>&1"
    rm -rf "$root/build"; touch "$root/opt/py311/.complete"
  fi
  # pip there reaches this machine's index through its configuration and certificates, copied in for the run.
  rm -rf "$root/tmp/wheel"; mkdir -p "$root/tmp/wheel/dist" "$root/tmp/wheel/pip"
  cp "$wheel" "$root/tmp/wheel/dist/"; cp assets/noon_grass_1k.hdr "$root/tmp/wheel/"
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  cp "$(python3 -c 'import ssl; print(ssl.get_default_verify_paths().openssl_cafile)')" "$root/tmp/wheel/pip/ca.crt"
  in_root /opt/py311/bin/python3.11 -m venv /tmp/wheel/venv
  in_root env PIP_CERT=/tmp/wheel/pip/ca.crt /tmp/wheel/venv/bin/pip install -q --disable-pip-version-check \
    /tmp/wheel/dist/"$(basename "$wheel")"
  options=(--lights 32 --refit --evaluate --effects diffuse,shadow)
  in_root /tmp/wheel/venv/bin/probelights bake /tmp/wheel/noon_grass_1k.hdr "${options[@]}" -q -o /tmp/wheel/there.json
  in_root /tmp/wheel/venv/bin/python -c "import json, probelights; r = probelights.bake_file('/tmp/wheel/noon_grass_1k.hdr',
    lights=16); json.dump([l.tolist() for l in (r['lights']['direction'], r['lights']['rgb'])], open('/tmp/wheel/module.json', 'w'))"
  "$cli" bake assets/noon_grass_1k.hdr "${options[@]}" -q -o "$root/tmp/wheel/here.json"
  "$cli" bake assets/noon_grass_1k.hdr --lights 16 -q -o "$root/tmp/wheel/here16.json"
  python3 - "$root/tmp/wheel" <<'PY'
import json, sys
d = sys.argv[1]
there, here = (json.load(open("%s/%s.json" % (d, n))) for n in ("there", "here"))
for r in (there, here):
    r.pop("timings_ms"); r["source"].pop("path"); evaluation = r.pop("evaluation")
    r["lights"] = [{k: v for k, v in l.items() if k not in ("rgb", "energy_share")} for l in r["lights"]]
assert there == here, "the command's lights there differ from this machine's"
e1, e2 = json.load(open(d + "/there.json"))["evaluation"], json.load(open(d + "/here.json"))["evaluation"]
worst = max(abs(e1[k] - e2[k]) / abs(e2[k]) for k in ("diffuse", "shadow"))
rgb = max(abs(a - b) / abs(b) for l1, l2 in zip(json.load(open(d + "/there.json"))["lights"],
                                                json.load(open(d + "/here.json"))["lights"])
          for a, b in zip(l1["rgb"], l2["rgb"]) if b)
assert worst < 1e-12 and rgb < 1e-9, (worst, rgb)
module = json.load(open(d + "/module.json"))
lights = json.load(open(d + "/here16.json"))["lights"]
assert module == [[l["direction"] for l in lights], [l["rgb"] for l in lights]], "the module's lights differ"
print("wheel on glibc 2.31: the command's regions and directions and the module's 16 lights equal build/bin's bit "
      "for bit; refit rgb within %.1e, errors within %.1e (relative)" % (rgb, worst))
PY
  exit 0
fi

modules=${1:-build/addon/probe_lights}
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
