#!/usr/bin/env bash
# Configures and builds wavebench into build/ (or $WAVEBENCH_BUILD_DIR).
# Usage: scripts/build.sh [--main] [cmake options...]
#   --main  only what the main job runs: the `wavebench` CLI and the libraries it links (no
#           tests, benchmarks, daemon or console); the same build folder serves both, so a
#           later full build reuses every object.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${WAVEBENCH_BUILD_DIR:-build}
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
targets=()
options=(-DWAVEBENCH_BUILD_TESTS=ON -DWAVEBENCH_BUILD_BENCHMARKS=ON -DWAVEBENCH_BUILD_CONSOLE=ON)
if [[ "${1:-}" == "--main" ]]; then
  shift
  targets=(--target wavebench)
  options=(-DWAVEBENCH_BUILD_TESTS=OFF -DWAVEBENCH_BUILD_BENCHMARKS=OFF -DWAVEBENCH_BUILD_CONSOLE=OFF)
fi
cmake -S . -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DWAVEBENCH_WERROR="${WAVEBENCH_WERROR:-ON}" "${options[@]}" "$@" >/dev/null
cmake --build "$build_dir" -j"${WAVEBENCH_JOBS:-2}" "${targets[@]}"
