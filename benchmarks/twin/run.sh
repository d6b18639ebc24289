#!/usr/bin/env bash
# Twin benchmark: C++ (median of 5 runs) against scipy's solve_ivp on the same equations.
# Usage: benchmarks/twin/run.sh [BUILD_DIR] [OUT_DIR]   (build first: scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
out=${2:-out/twin-benchmark}
"$build/benchmarks/twin/twin_benchmark" --config configs/twin/xb-80-134h.yaml --repeat 5 --out "$out"
/usr/bin/python3 benchmarks/twin/scipy_reference.py "$out"
