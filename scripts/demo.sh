#!/usr/bin/env bash
# The main job on the bundled probe: install what is missing, build the command, bake 16 lights, show the result.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
# The command alone: no tests, benchmarks, Python module or add-on (those need what `install-deps.sh --test` adds).
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPROBELIGHTS_BUILD_TESTS=OFF -DPROBELIGHTS_BUILD_BENCHMARKS=OFF \
  -DPROBELIGHTS_BUILD_PYTHON=OFF >/dev/null
cmake --build build -j"$(nproc)" --target probelights >/dev/null
mkdir -p out
build/bin/probelights bake assets/noon_grass_1k.hdr --method variance --lights 16 \
  --evaluate --effects diffuse,shadow -o out/demo_lights.json --preview out/demo_regions.png
echo
echo "lights (JSON): out/demo_lights.json"
echo "regions and lights drawn on the probe: out/demo_regions.png"
