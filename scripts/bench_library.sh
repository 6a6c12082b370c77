#!/usr/bin/env bash
# A whole library in one command against its reads alone (issue 10: within 1.5x). Makes a folder of 100 1K
# probes (the four 1K .hdr of ../shared/hdri, 25 copies each; without ../shared, 100 copies of the bundled
# probe), then, each 6 times (medians):
#   the reads alone   every file read whole, one after another, in one process (probelights_decode_bench's
#                     BM_LibraryReads; the process start is not counted)
#   the library       probelights bake DIR --out-dir OUT --lights 64, the whole process (start-up included)
# Run on an idle machine:  bash scripts/bench_library.sh [build/bin]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
bin="${1:-$here/build/bin}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/lib"
sources=("$here"/../shared/hdri/*_1k.hdr)
[ -e "${sources[0]}" ] || sources=("$here/assets/noon_grass_1k.hdr")
for i in $(seq 0 99); do
  cp "${sources[$((i % ${#sources[@]}))]}" "$(printf '%s/lib/p%03d.hdr' "$work" "$i")"
done
echo "library: 100 copies of ${#sources[@]} probe(s): $(basename -a "${sources[@]}" | tr '\n' ' ')"

reads_ms=$(PROBELIGHTS_LIBRARY="$work/lib" "$bin/probelights_decode_bench" --benchmark_filter=LibraryReads \
  --benchmark_format=json 2>/dev/null | python3 -c '
import json, sys
runs = [b["real_time"] for b in json.load(sys.stdin)["benchmarks"] if b.get("run_type") == "iteration"]
runs.sort()
print(runs[len(runs) // 2])')

times=()
for run in 1 2 3 4 5 6; do
  rm -rf "$work/out"
  start=$(date +%s.%N)
  "$bin/probelights" bake "$work/lib" --out-dir "$work/out" --lights 64 > /dev/null
  end=$(date +%s.%N)
  times+=("$(python3 -c "print(($end - $start) * 1000)")")
done
python3 - "$reads_ms" "${times[@]}" <<'EOF'
import sys
reads = float(sys.argv[1])
runs = sorted(float(t) for t in sys.argv[2:])
median = (runs[2] + runs[3]) / 2
print(f"reads alone  {reads:7.0f} ms (median of 6, one process, start not counted)")
print(f"library      {median:7.0f} ms (median of 6, {runs[0]:.0f}-{runs[-1]:.0f}; the whole process)")
print(f"ratio        {median / reads:7.2f}x (issue 10 asks at most 1.5x)")
EOF
