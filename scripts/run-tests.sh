#!/usr/bin/env bash
# All tests: installs what is missing (the vcan VM's packages too), builds with warnings as
# errors, runs the unit and integration suites with ctest, then the vcan suite inside a VM.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --with-vm
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j2 -LE vcan --timeout 900
if [[ -x scripts/vcan-vm/run-vcan-tests.sh ]]; then
  bash scripts/vcan-vm/run-vcan-tests.sh build
fi
