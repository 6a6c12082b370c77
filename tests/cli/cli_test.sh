#!/usr/bin/env bash
# The CLI as a user runs it: one clear line on stderr and exit code 2 for every bad input; a good bake writes
# JSON with the documented fields and a preview PNG.
#   cli_test.sh PROBELIGHTS_BINARY REAL_PROBE
set -u
bin=$1 probe=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0 failed=0

expect_error() {  # name, expected text in the message, args...
  local name=$1 text=$2; shift 2
  "$bin" "$@" >"$tmp/out" 2>"$tmp/err"
  local code=$? lines
  lines=$(wc -l <"$tmp/err")
  if [[ $code -eq 2 && $lines -eq 1 ]] && grep -q "^probelights: error: .*$text" "$tmp/err"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1)); echo "FAIL $name: exit $code, stderr:"; cat "$tmp/err"
  fi
}

expect_error "missing file" "no such file" bake "$tmp/nope.exr"
echo "not an image" >"$tmp/garbage.hdr"
expect_error "unreadable file" "cannot read probe" bake "$tmp/garbage.hdr"
expect_error "zero lights" "at least 1" bake "$probe" --lights 0
expect_error "negative lights" "at least 1" bake "$probe" --lights -3
expect_error "lights not a number" "whole number" bake "$probe" --lights many
expect_error "absurd light count" "at most 65536" bake "$probe" --lights 5000000
expect_error "unknown method" "unknown method" bake "$probe" --method magic
expect_error "unknown option" "unknown option" bake "$probe" --frobnicate
expect_error "no probe" "no probe" bake
expect_error "unknown command" "unknown command" frobnicate
expect_error "unknown sun angles" "unknown sun angles 'soft'" bake "$probe" --sun-angles soft
expect_error "unknown sun profile" "unknown sun profile" bake "$probe" --sun-profile round
expect_error "unknown preset" "--preset takes blender or blender-eevee, got 'blend'" bake "$probe" --preset blend
# A 2x2 PFM: square, so auto projection must ask; with a NaN, refused unless --nonfinite=zero.
printf 'PF\n2 2\n-1.0\n' >"$tmp/square.pfm"
python3 -c "import struct,sys; sys.stdout.buffer.write(struct.pack('<12f', *([1.0]*12)))" >>"$tmp/square.pfm"
expect_error "ambiguous projection" "say which it is: --projection latlong, mirror-ball or angular" bake "$tmp/square.pfm"
printf 'PF\n4 2\n-1.0\n' >"$tmp/nan.pfm"
python3 -c "import struct,sys; v=[1.0]*24; v[4]=float('nan'); sys.stdout.buffer.write(struct.pack('<24f', *v))" >>"$tmp/nan.pfm"
expect_error "NaN pixels" "1 NaN/Inf samples, first at pixel (1, 1); to read them as 0: --nonfinite zero$" bake "$tmp/nan.pfm"
# A PFM's rows are stored bottom to top, whatever its size: one over 32 MB is opened by name, not read from memory
# (image.cpp), and OpenImageIO flips it only when asked (pnm:pfmflip); unasked, this NaN was reported at row 0.
python3 -c "import array,sys; w,h=4096,1024; a=array.array('f',[1.0])*(w*h*3); a[16]=float('nan'); sys.stdout.buffer.write(b'PF\n%d %d\n-1.0\n'%(w,h)+a.tobytes())" >"$tmp/big.pfm"
expect_error "NaN pixels in a PFM over 32 MB" "first at pixel (5, 1023);" bake "$tmp/big.pfm" --projection latlong
rm -f "$tmp/big.pfm"
expect_error "light type without glTF" "add --gltf FILE" bake "$probe" --light-type point
expect_error "distance for suns" "add --light-type point" bake "$probe" --gltf "$tmp/x.gltf" --distance 3
expect_error "bad light type" "sun or point" bake "$probe" --gltf "$tmp/x.gltf" --light-type spot
expect_error "zero distance" "above 0" bake "$probe" --gltf "$tmp/x.gltf" --light-type point --distance 0
expect_error "glTF in a library" "drop -o / --preview / --gltf" bake "$probe" --out-dir "$tmp/lib" --gltf "$tmp/x.gltf"
expect_error "glTF over the probe" "is the probe itself" bake "$probe" --gltf "$probe"
expect_error "USD dome without USD" "add --usd FILE" bake "$probe" --usd-dome reflections
expect_error "residual dome without a residual" "add it" bake "$probe" --usd "$tmp/x.usda" --usd-dome residual
expect_error "bad USD dome" "none, reflections or residual" bake "$probe" --usd "$tmp/x.usda" --usd-dome sky
expect_error "USD in a library" "drop -o / --preview / --gltf / --usd" bake "$probe" --out-dir "$tmp/lib" --usd "$tmp/x.usda"
expect_error "USD over the probe" "is the probe itself" bake "$probe" --usd "$probe"
expect_error "residual with a refit" "leave out the refit" bake "$probe" --residual "$tmp/r.exr" --refit
expect_error "residual in a library" "--residual" bake "$probe" --out-dir "$tmp/lib" --residual "$tmp/r.exr"
expect_error "bad source level" "source-level takes a multiple" bake "$probe" --source-level -2
expect_error "USD dome of a mirror ball" "lat-long dome" bake "$tmp/square.pfm" --projection mirror-ball --usd "$tmp/b.usda" --usd-dome reflections

check() {  # name, command
  if eval "$2"; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL $1"; fi
}
check "nonfinite zero proceeds" "'$bin' bake '$tmp/nan.pfm' --nonfinite=zero --lights 2 -q -o '$tmp/nan.json'"
check "bake writes JSON and a preview" \
  "'$bin' bake '$probe' --lights 8 --method median-cut -o '$tmp/l.json' --preview '$tmp/p.png' >'$tmp/summary'"
check "JSON has the documented fields and conserves energy" "python3 - '$tmp/l.json' <<'PY'
import json, sys, math
d = json.load(open(sys.argv[1]))
assert set(d['source']) >= {'path', 'width', 'height', 'projection'}, d['source']
assert d['method'] == 'median-cut' and len(d['lights']) == 8
for l in d['lights']:
    assert set(l) >= {'direction', 'rgb', 'solid_angle', 'angular_radius', 'angle', 'rect', 'energy_share'}
    assert abs(math.hypot(*l['direction']) - 1) < 1e-9
assert set(d['timings_ms']) >= {'load', 'tables', 'partition'}
for k in range(3):
    s = sum(l['rgb'][k] for l in d['lights'])
    assert abs(s - d['total_rgb'][k]) <= 1e-6 * d['total_rgb'][k], (s, d['total_rgb'])
PY"
check "preview is a PNG" "head -c 8 '$tmp/p.png' | od -An -c | grep -q 'P   N   G'"
check "bake writes glTF lights" \
  "'$bin' bake '$probe' --lights 8 --gltf '$tmp/l.gltf' -q && python3 -c \"import json,sys; d=json.load(open(sys.argv[1])); assert len(d['nodes']) == 8 and d['extensionsUsed'] == ['KHR_lights_punctual']\" '$tmp/l.gltf'"
check "bake writes USD lights" \
  "'$bin' bake '$probe' --lights 8 --usd '$tmp/l.usda' --light-type point -q && [[ \$(grep -c 'def SphereLight' '$tmp/l.usda') -eq 8 ]] && [[ ! -e '$tmp/b.usda' ]]"
# Every format the usage lists (the core's exporters) in one run: each file written whole, the CSV's suns the
# JSON's lights.
check "bake writes every listed format at once" "formats=\$('$bin' --help | sed -n 's/^  --\\([a-z]*\\) FILE  *write the lights as .*/\\1/p') && [[ \$(echo \$formats) == 'gltf usd csv' ]] && args=() && for f in \$formats; do args+=(--\$f '$tmp/all.'\$f); done && '$bin' bake '$probe' --lights 8 -o '$tmp/all.json' -q \"\${args[@]}\" && missing=0 && for f in \$formats; do [[ -s '$tmp/all.'\$f ]] || missing=1; done && [[ \$missing == 0 ]] && python3 - '$tmp/all.json' '$tmp/all.csv' <<'PY'
import csv, json, sys
lights = json.load(open(sys.argv[1]))['lights']
rows = list(csv.DictReader(open(sys.argv[2])))
assert [r['type'] for r in rows] == ['sun'] * 8, rows
for l, r in zip(lights, rows):
    assert [float(r[k]) for k in 'rgb'] == l['rgb'], (l, r)
    assert max(abs(float(r[k]) - d) for k, d in zip('xyz', l['direction'])) < 1e-12, (l, r)
PY"
check "bake writes a residual and says lamps + residual give back the probe" \
  "'$bin' bake '$probe' --lights 4 --residual '$tmp/res.exr' --source-share 40% >'$tmp/res.txt' && head -c 4 '$tmp/res.exr' | od -An -tx1 | grep -q '76 2f 31 01' && grep -q 'lamps + residual' '$tmp/res.txt' && grep -q '40.0% of it' '$tmp/res.txt' && [[ ! -e '$tmp/r.exr' ]]"
check "summary shows timings and energy" "grep -q 'time (ms)' '$tmp/summary' && grep -q 'max rel. diff' '$tmp/summary'"
check "version" "'$bin' --version | grep -q '^probelights [0-9]'"
check "JSON to stdout" "'$bin' bake '$probe' --lights 2 -o - | python3 -c 'import json,sys; json.load(sys.stdin)'"

# Spherical harmonics: coefficients, samples, and the sh light method.
expect_error "sh without bands" "no SH bands given; give them: --bands B (at least 1)" sh "$probe"
expect_error "sample without bands" "no SH bands given; give them: --bands" sample "$probe" --samples 10
check "sample's defaults are the module's (sh_request.h)" "'$bin' sample '$probe' --bands 4 -o '$tmp/sd.json' && python3 -c \"import json; d=json.load(open('$tmp/sd.json')); assert d['epsilon'] == 0.01 and len(d['pdf']) == 1024 and d['depth'] == 8 and d['seed'] == 1\""
expect_error "sh takes no bake options" "unknown option '--lights'" sh "$probe" --bands 4 --lights 3
expect_error "sample with a bad epsilon" "epsilon must be in" sample "$probe" --bands 4 --samples 10 --epsilon 0.9
check "sh writes coefficients" "'$bin' sh '$probe' --bands 4 --irradiance -o '$tmp/sh.json' && python3 - '$tmp/sh.json' <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert d['bands'] == 4 and len(d['coefficients']) == 16 and d['quantity'] == 'irradiance', d.keys()
PY"
check "sample writes directions and pdfs" "'$bin' sample '$probe' --bands 6 --epsilon 0.01 --samples 100 -o '$tmp/s.json' && python3 - '$tmp/s.json' <<'PY'
import json, sys, math
d = json.load(open(sys.argv[1]))
assert len(d['directions']) == 100 and len(d['pdf']) == 100
assert all(p > 0 for p in d['pdf']) and all(abs(math.hypot(*v) - 1) < 1e-9 for v in d['directions'])
PY"
check "bake --method sh" "'$bin' bake '$probe' --method sh --lights 8 --bands 6 -o '$tmp/shl.json' -q && python3 -c \"import json; d=json.load(open('$tmp/shl.json')); assert d['method']=='sh' and len(d['lights'])==8 and d['sh']['bands']==6\""

# What accuracy costs: evaluation, refit, auto count, the tradeoff report and its plot.
expect_error "bad effect" "unknown effect" bake "$probe" --evaluate --effects caustics
expect_error "bad tolerance" "between 0 and 100%" bake "$probe" --max-error 200%
check "bake --refit reports errors and the energy shift" "'$bin' bake '$probe' --lights 16 --refit --effects diffuse,shadow >'$tmp/refit.txt' && grep -q 'error      diffuse' '$tmp/refit.txt' && grep -q 'energy shift' '$tmp/refit.txt'"
check "bake --refit-directions" "'$bin' bake '$probe' --lights 16 --refit-directions -q -o '$tmp/rd.json' && python3 -c \"import json; d=json.load(open('$tmp/rd.json')); assert d['evaluation']['refit'] and d['evaluation']['diffuse'] < 0.02\""
# A preset is the add-on's recipe by name: the same lights as its options spelled out, whatever its place among
# the others, which change it.
check "bake --preset is the add-on's options" "'$bin' bake '$probe' --preset blender-eevee -q -o '$tmp/pe.json' && '$bin' bake '$probe' --lights 64 --method variance --cuts auto --centroid energy2 --refit --refit-directions --evaluate --effects diffuse,shadow --evaluator-width 512 --sun-angles fit --sun-profile cone --sun-cones above-horizon -q -o '$tmp/px.json' && '$bin' bake '$probe' --lights 8 --preset blender -q -o '$tmp/p8.json' && python3 -c \"import json; a, b, c = (json.load(open('$tmp/%s.json' % n)) for n in ('pe', 'px', 'p8')); [d.pop('timings_ms') for d in (a, b)]; assert a == b and len(a['lights']) == 64; assert len(c['lights']) == 8 and c['evaluation']['sun_cones'] == 'free' and c['evaluation']['refit']\""
check "bake --both-cuts changes a preset given after it" "'$bin' bake '$probe' --both-cuts --preset blender -q -o - | python3 -c \"import json, sys; assert 'both cuts fitted: variance kept' in [n['text'] for n in json.load(sys.stdin)['notes']]\""
check "bake --max-error picks a count" "'$bin' bake '$probe' --max-error 2% -o '$tmp/auto.json' -q && python3 -c \"import json; d=json.load(open('$tmp/auto.json')); a=d['evaluation']; assert a['auto_count']['met'] and a['diffuse'] <= 0.02 and len(d['lights']) == a['auto_count']['lights']\""
check "tradeoff table, JSON and plot" "'$bin' tradeoff '$probe' --counts 4,16 --methods variance,sh -o '$tmp/t.json' --plot '$tmp/t.png' >'$tmp/t.txt' && head -c 8 '$tmp/t.png' | od -An -c | grep -q 'P   N   G' && python3 -c \"import json; d=json.load(open('$tmp/t.json')); assert len(d['rows']) == 12, len(d['rows'])\""
# The tradeoff takes the bake's options by their names (one table, tradeoff.h): a preset makes its rows as the
# preset's bake, the options after it change it; a bake's own option is refused.
check "a switch turned off against the preset: --refit=off" "'$bin' bake '$probe' --lights 8 --preset blender --refit=off -q -o '$tmp/pr0.json' && '$bin' --help | grep -q '^  --refit\\[=off\\]' && python3 -c \"import json; e=json.load(open('$tmp/pr0.json'))['evaluation']; assert not e['refit'] and e['sun_angles'] == 'fit', e\""
expect_error "a switch's bad value" "--refit takes on or off, got 'maybe'" bake "$probe" --refit=maybe
expect_error "a flag with a value" "--quiet takes no value" bake "$probe" --quiet=yes
check "evaluate: a bake's own lights, judged by its preset, give its errors" "'$bin' bake '$probe' --preset blender -n 16 -q -o '$tmp/ev16.json' && '$bin' evaluate '$probe' '$tmp/ev16.json' --preset blender -o '$tmp/ev.json' >'$tmp/ev.txt' && grep -q '^error      diffuse' '$tmp/ev.txt' && python3 -c \"import json; b=json.load(open('$tmp/ev16.json'))['evaluation']; e=json.load(open('$tmp/ev.json')); assert set(e) == {'diffuse', 'shadow'} and all(abs(e[k] - b[k]) <= 1e-12 * b[k] for k in e), (b, e)\""
expect_error "evaluate without lights" "probelights evaluate PROBE LIGHTS.json" evaluate "$probe"
expect_error "evaluate of a file that is not JSON" "is not JSON" evaluate "$probe" "$probe"
expect_error "evaluate over the lights" "is the lights' file" evaluate "$probe" "$tmp/ev16.json" -o "$tmp/ev16.json"
expect_error "evaluate takes no bake options" "unknown option '--lights'" evaluate "$probe" "$tmp/ev16.json" --lights 3
check "tradeoff --preset: the rows the preset's bake makes" "'$bin' tradeoff '$probe' --counts 16 --methods variance --resolutions auto --preset blender -o '$tmp/tp.json' >/dev/null && '$bin' bake '$probe' --preset blender --cuts one -n 16 -q -o '$tmp/tb.json' && python3 -c \"import json; r=json.load(open('$tmp/tp.json'))['rows']; e=json.load(open('$tmp/tb.json'))['evaluation']; assert [x['refit'] for x in r] == [False, True] and r[1]['resolution'] == 'auto'; assert all(abs(r[1][k] - e[k]) <= 1e-12 * e[k] for k in ('diffuse', 'shadow')), (r, e)\""
expect_error "tradeoff refuses a bake's own option" "unknown option '--lights'" tradeoff "$probe" --lights 4
expect_error "tradeoff refuses an empty count" "comma-separated list" tradeoff "$probe" --counts 4,,16

# A library in one command: a bad file among good ones is reported on one line and the rest are baked (exit
# 3); each result equals the single-probe bake; an output folder that cannot be made is refused before any work.
mkdir -p "$tmp/lib" "$tmp/lib2"
cp "$probe" "$tmp/lib/a.hdr"
cp "$tmp/square.pfm" "$tmp/lib/b.pfm"
echo junk >"$tmp/lib/broken.hdr"
cp "$probe" "$tmp/lib2/a.hdr"
"$bin" bake "$tmp/lib" "$tmp/lib2" --projection latlong --lights 12 --out-dir "$tmp/library" -q 2>"$tmp/lib.err"
code=$?
check "library bake: exit 3 and one line for the bad probe" "[[ $code -eq 3 ]] && [[ \$(wc -l <'$tmp/lib.err') -eq 1 ]] && grep -q 'broken.hdr' '$tmp/lib.err'"
"$bin" bake "$probe" --lights 12 -o "$tmp/single.json" -q
check "library bake: results equal single bakes, summary, unique names" "python3 -c \"
import json
s = json.load(open('$tmp/library/summary.json'))
assert s['probes'] == 4 and s['baked'] == 3 and s['failed'] == 1, s
assert [r.get('output') for r in s['results']] == ['a.json', 'b.json', None, 'a_2.json'], s['results']
one, lib = json.load(open('$tmp/single.json')), json.load(open('$tmp/library/a.json'))
assert one['lights'] == lib['lights'] and one['total_rgb'] == lib['total_rgb']
assert json.load(open('$tmp/library/a_2.json'))['lights'] == one['lights']
\""
check "library bake: nothing half-written" "! ls '$tmp/library' | grep -q part"
touch "$tmp/a-file"
expect_error "library bake into a folder that cannot be made" "cannot write to output directory" bake "$tmp/lib" --out-dir "$tmp/a-file/out"
check "library bake: a refused folder leaves nothing" "[[ ! -e '$tmp/a-file/out' ]]"
check "library bake: globs" "'$bin' bake '$tmp/lib/*.hdr' --out-dir '$tmp/out2' -q 2>/dev/null; [[ -f '$tmp/out2/a.json' ]]"

# A working grid coarser than the image (here 256 wide, cells of 4 px on the 1K probe): with nothing else asked
# the probe is read band by band into the grid, never whole; the lights are those of a whole load (a preview
# needs the pixels, so that bake loads it whole), in one bake and in a library.
"$bin" bake "$probe" --lights 24 --resolution 256 -o "$tmp/banded.json" >"$tmp/banded.txt"
"$bin" bake "$probe" --lights 24 --resolution 256 -o "$tmp/whole.json" --preview "$tmp/whole.png" -q
"$bin" bake "$probe" --lights 24 --resolution 256 --out-dir "$tmp/banded_lib" -q
check "band-by-band bake: the lights of a whole load, and it says so" "grep -q 'tables .* of it, while reading' '$tmp/banded.txt' && python3 -c \"
import json
b, w, l = (json.load(open(f)) for f in ('$tmp/banded.json', '$tmp/whole.json', '$tmp/banded_lib/$(basename "$probe" .hdr).json'))
assert b['lights'] == w['lights'] == l['lights'] and b['total_rgb'] == w['total_rgb']
assert any('band by band' in n['text'] for n in b['notes']) and not any('band by band' in n['text'] for n in w['notes']), b['notes']
\""
printf 'PF\n16 8\n-1.0\n' >"$tmp/nan8.pfm"
python3 -c "import struct,sys; v=[1.0]*384; v[300]=float('nan'); sys.stdout.buffer.write(struct.pack('<384f', *v))" >>"$tmp/nan8.pfm"
expect_error "NaN pixels, read band by band" "1 NaN/Inf samples, first at pixel (4, 1)" bake "$tmp/nan8.pfm" --resolution 4

check "fitted sun angles, points and the profile in the JSON" "'$bin' bake '$probe' --lights 8 --effects diffuse,shadow --evaluate -q -o '$tmp/fit.json' && '$bin' bake '$probe' --lights 8 --effects diffuse,shadow --evaluate --sun-angles points --sun-profile disc -q -o '$tmp/pts.json' && python3 - '$tmp/fit.json' '$tmp/pts.json' <<'PY'
import json, math, sys
fit, pts = (json.load(open(p)) for p in sys.argv[1:])
assert fit['evaluation']['sun_angles'] == 'fit' and fit['evaluation']['sun_profile'] == 'cone'
assert pts['evaluation']['sun_angles'] == 'points' and pts['evaluation']['sun_profile'] == 'disc'
assert all(0 <= l['angle'] <= math.pi for l in fit['lights']) and any(l['angle'] > 0 for l in fit['lights'])
assert all(l['angle'] == 0 for l in pts['lights'])
assert fit['evaluation']['shadow'] < pts['evaluation']['shadow']
PY"
# bake-sequence: frames of 64 x 32, a sky of 1 and a bright pixel moving along the horizon (frames 1-4 of
# seq_####.pfm), one of another size, and a pattern's mistakes.
mkdir -p "$tmp/seq" "$tmp/odd"
python3 - "$tmp" <<'PY'
import struct, sys
def frame(path, w, h, sun):
    v = [1.0] * (w * h * 3)
    for k in range(3): v[(h // 2 * w + sun) * 3 + k] = 500.0
    with open(path, 'wb') as f: f.write(b'PF\n%d %d\n-1.0\n' % (w, h) + struct.pack('<%df' % len(v), *v))
for n in range(1, 5): frame('%s/seq/seq_%04d.pfm' % (sys.argv[1], n), 64, 32, 10 + 3 * n)
frame('%s/odd/o_0001.pfm' % sys.argv[1], 64, 32, 10); frame('%s/odd/o_0002.pfm' % sys.argv[1], 32, 16, 10)
PY
check "bake-sequence keeps N lights with ids, each frame's light exact" "'$bin' bake-sequence '$tmp/seq/seq_####.pfm' --lights 6 --evaluate -q -o '$tmp/seq.json' >'$tmp/seq.txt' && grep -q '^4 frames: ' '$tmp/seq.txt' && python3 - '$tmp/seq.json' <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert [f['frame'] for f in d['frames']] == [1, 2, 3, 4] and d['requested_lights'] == 6 and d['summary']['frames'] == 4
for f in d['frames']:
    assert [l['id'] for l in f['lights']] == list(range(6))
    for k in range(3):
        assert abs(sum(l['rgb'][k] for l in f['lights']) - f['total_rgb'][k]) <= 1e-9 * f['total_rgb'][k]
    assert f['evaluation']['diffuse'] < 0.2 and f['source']['width'] == 64
sun = [max(f['lights'], key=lambda l: l['rgb'][1])['id'] for f in d['frames']]
assert len(set(sun)) == 1, sun
PY"
check "bake-sequence --frames takes a range" "'$bin' bake-sequence '$tmp/seq/seq_####.pfm' --frames 2-3 --lights 2 -q -o - | python3 -c 'import json,sys; assert [f[\"frame\"] for f in json.load(sys.stdin)[\"frames\"]] == [2, 3]'"
expect_error "sequence without #" "has # where the frame number goes" bake-sequence "$tmp/seq/seq_0001.pfm"
expect_error "sequence of no file" "no file matches" bake-sequence "$tmp/seq/none_####.pfm"
expect_error "sequence with a missing frame" "frame 5 of 3-6 has no file" bake-sequence "$tmp/seq/seq_####.pfm" --frames 3-6
expect_error "sequence of two sizes" "frame 2 is 32x16 latlong, the sequence's first frame 64x32 latlong" bake-sequence "$tmp/odd/o_####.pfm"
expect_error "sequence by sh" "not by the sh method" bake-sequence "$tmp/seq/seq_####.pfm" --method sh
expect_error "sequence smoothness" "the smoothness is a number from 0" bake-sequence "$tmp/seq/seq_####.pfm" --smoothness -1
check "bake-sequence finishes frames as bake does (fitted angles, refit)" "'$bin' bake-sequence '$tmp/seq/seq_####.pfm' --lights 4 --sun-angles fit --refit -q -o - | python3 -c 'import json,sys; f = json.load(sys.stdin)[\"frames\"]; assert all(abs(x[\"energy_shift\"]) < 0.5 and len(x[\"lights\"]) == 4 for x in f), f'"
check "bake-sequence's refit keeps every frame's energy exact (--exact-energy off lets it move)" "'$bin' bake-sequence '$tmp/seq/seq_####.pfm' --lights 4 --sun-angles fit --refit -q -o - | python3 -c 'import json,sys; f = json.load(sys.stdin)[\"frames\"]; assert all(abs(sum(map(sum, (l[\"rgb\"] for l in x[\"lights\"]))) / sum(x[\"total_rgb\"]) - 1) < 1e-9 for x in f), f' && '$bin' bake-sequence '$tmp/seq/seq_####.pfm' --lights 4 --refit --exact-energy off -q -o - >/dev/null"
check "bake-sequence refuses --fit-width 0 in one line" "! '$bin' bake-sequence '$tmp/seq/seq_####.pfm' --fit-width 0 -q -o - 2>$tmp/fw.err && grep -q 'fit-width takes auto or a width of at least 1 pixel' $tmp/fw.err && test \$(wc -l < $tmp/fw.err) = 1"
check "bake-sequence refuses --exact-energy maybe in one line" "! '$bin' bake-sequence '$tmp/seq/seq_####.pfm' --exact-energy maybe -q -o - 2>$tmp/ee.err && grep -q 'exact-energy takes on or off' $tmp/ee.err && test \$(wc -l < $tmp/ee.err) = 1"
expect_error "sequence evaluator width" "width of at least 1" bake-sequence "$tmp/seq/seq_####.pfm" --evaluator-width 0
expect_error "sequence frames backwards" "the first frame before the last" bake-sequence "$tmp/seq/seq_####.pfm" --frames 4-2
expect_error "sequence fps" "--fps takes frames per second" bake-sequence "$tmp/seq/seq_####.pfm" --usd "$tmp/s.usda" --fps 0
expect_error "sequence overwriting a frame" "" bake-sequence "$tmp/seq/seq_####.pfm" -o "$tmp/seq/seq_0002.pfm"
expect_error "sequence export options without a file" "give --usd or --gltf" bake-sequence "$tmp/seq/seq_####.pfm" --fps 30
check "bake-sequence --gltf keys every light on every frame" "'$bin' bake-sequence '$tmp/seq/seq_####.pfm' --lights 3 -q --gltf '$tmp/seq.gltf' --fps 30 && python3 - '$tmp/seq.gltf' <<'PY'
import base64, json, struct, sys
d = json.load(open(sys.argv[1]))
a = d['animations'][0]
assert len(a['channels']) == 9 and 'KHR_animation_pointer' in d['extensionsUsed'], a['channels']
data = base64.b64decode(d['buffers'][0]['uri'].split(',', 1)[1])
assert len(data) == d['buffers'][0]['byteLength']
view = d['bufferViews'][d['accessors'][a['samplers'][0]['input']]['bufferView']]
times = struct.unpack('<4f', data[view['byteOffset']:view['byteOffset'] + 16])
assert [round(t * 30) for t in times] == [1, 2, 3, 4], times
PY"
echo "$passed passed, $failed failed"
[[ $failed -eq 0 ]]
