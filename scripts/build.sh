#!/usr/bin/env bash
# Configures and builds wavebench into build/ (or $WAVEBENCH_BUILD_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${WAVEBENCH_BUILD_DIR:-build}
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S . -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DWAVEBENCH_WERROR="${WAVEBENCH_WERROR:-ON}" "$@" >/dev/null
cmake --build "$build_dir" -j"${WAVEBENCH_JOBS:-2}"
