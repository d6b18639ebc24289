#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the digital twin's reference case
# (XB-80-134H), writing time series, summary and plots to out/xb-80-134h/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
out=${1:-out/xb-80-134h}
./build/src/cli/wavebench sim configs/twin/xb-80-134h.yaml --out "$out"
