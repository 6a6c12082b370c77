#!/usr/bin/env bash
# The main job on the bundled probe: install what is missing, build the command, bake 16 lights, show the result.
# (ctest's "demo" test runs this same script into its own build folder, PROBELIGHTS_DEMO_BUILD and _OUT, with
# PROBELIGHTS_DEMO_INSTALL=0, the packages being the test command's already, and GoogleTest hidden from CMake by
# PROBELIGHTS_DEMO_CMAKE_ARGS, as a machine with only this script's packages has none.)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${PROBELIGHTS_DEMO_BUILD:-build} out=${PROBELIGHTS_DEMO_OUT:-out}
[[ ${PROBELIGHTS_DEMO_INSTALL:-1} == 0 ]] || scripts/install-deps.sh
# The command alone: no tests, benchmarks, Python module or add-on (those need what `install-deps.sh --test` adds).
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DPROBELIGHTS_BUILD_TESTS=OFF -DPROBELIGHTS_BUILD_BENCHMARKS=OFF \
  -DPROBELIGHTS_BUILD_PYTHON=OFF ${PROBELIGHTS_DEMO_CMAKE_ARGS:-} >/dev/null
cmake --build "$build" -j"$(nproc)" --target probelights >/dev/null
mkdir -p "$out"
"$build"/bin/probelights bake assets/noon_grass_1k.hdr --method variance --lights 16 \
  --evaluate --effects diffuse,shadow -o "$out"/demo_lights.json --preview "$out"/demo_regions.png
echo
echo "lights (JSON): $out/demo_lights.json"
echo "regions and lights drawn on the probe: $out/demo_regions.png"
