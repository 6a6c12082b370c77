#!/usr/bin/env bash
# A whole library in one command against its reads alone (issue 10: within 1.5x). Makes a folder of 100 1K
# probes (the four 1K .hdr of ../shared/hdri, 25 copies each; without ../shared, 100 copies of the bundled
# probe), then, each 6 times (medians):
#   the reads alone   every file read whole, one after another, in one process (probelights_decode_bench's
#                     BM_LibraryReads; the process start is not counted)
#   the library       probelights bake DIR --out-dir OUT --lights 64, the whole process (start-up included),
#                     and inside it (summary.json's seconds: from the first load to the last result written)
#   the process start probelights --help, the whole process (OpenImageIO's libraries loaded and bound)
# Run on an idle machine:  bash bench/bench_library.sh [build/bin]
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

# Milliseconds a command takes as a whole process.
whole_ms() {
  local start end
  start=$(date +%s.%N)
  "$@" > /dev/null
  end=$(date +%s.%N)
  python3 -c "print(($end - $start) * 1000)"
}
times=() inside=() starts=()
for run in 1 2 3 4 5 6; do
  rm -rf "$work/out"
  times+=("$(whole_ms "$bin/probelights" bake "$work/lib" --out-dir "$work/out" --lights 64)")
  inside+=("$(python3 -c 'import json, sys; print(1000 * json.load(open(sys.argv[1]))["seconds"])' \
    "$work/out/summary.json")")
  starts+=("$(whole_ms "$bin/probelights" --help)")
done
python3 - "$reads_ms" "${times[*]}" "${inside[*]}" "${starts[*]}" <<'EOF'
import sys
reads = float(sys.argv[1])
def median(text):
    runs = sorted(float(t) for t in text.split())
    return (runs[2] + runs[3]) / 2, runs[0], runs[-1]
library, lo, hi = median(sys.argv[2])
inside, ilo, ihi = median(sys.argv[3])
start, slo, shi = median(sys.argv[4])
print(f"reads alone    {reads:7.0f} ms (median of 6, one process, start not counted)")
print(f"library        {library:7.0f} ms (median of 6, {lo:.0f}-{hi:.0f}; the whole process)")
print(f"  inside it    {inside:7.0f} ms ({ilo:.0f}-{ihi:.0f}; first load to last result, summary.json)")
print(f"process start  {start:7.0f} ms ({slo:.0f}-{shi:.0f}; probelights --help)")
print(f"ratio          {library / reads:7.2f}x (issue 10 asks at most 1.5x); inside the process "
      f"{inside / reads:.2f}x; the start alone {start / reads:.2f}x")
EOF
