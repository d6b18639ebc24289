#!/usr/bin/env bash
# All tests: installs what is missing (the vcan VM's packages too), builds with warnings as
# errors, runs the unit and integration suites with ctest, the vcan suite inside a small VM,
# and the fuzzers for a bounded time. Every stage runs; the exit status is non-zero if any
# failed. The last line sums the ctest counts of both suites (each counted once).
set -uo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --with-vm || exit 1
bash scripts/build.sh || exit 1

logs=build/test-logs
mkdir -p "$logs"
failed_stages=()

echo "== unit and integration tests (host)"
ctest --test-dir build --output-on-failure -j2 -LE vcan --timeout 900 2>&1 | tee "$logs/host.log"
[[ ${PIPESTATUS[0]} -eq 0 ]] || failed_stages+=(host)

echo "== vcan tests (inside the VM)"
bash scripts/vcan-vm/run-vcan-tests.sh build 2>&1 | tee "$logs/vcan.log"
[[ ${PIPESTATUS[0]} -eq 0 ]] || failed_stages+=(vcan)

echo "== fuzzers (${WAVEBENCH_FUZZ_SECONDS:-30} s each)"
bash scripts/run-fuzzers.sh "${WAVEBENCH_FUZZ_SECONDS:-30}" 2>&1 | tee "$logs/fuzz.log"
[[ ${PIPESTATUS[0]} -eq 0 ]] || failed_stages+=(fuzz)

# ctest prints "NN% tests passed, F tests failed out of T" for each suite.
passed=0
failed=0
while read -r f t; do
  passed=$((passed + t - f))
  failed=$((failed + f))
done < <(for log in "$logs/host.log" "$logs/vcan.log"; do
  # The VM runner repeats its ctest summary after the run: one count per suite.
  grep -hoE '[0-9]+ tests failed out of [0-9]+' "$log" | tail -n 1
done | awk '{print $1, $6}')
if ((${#failed_stages[@]})); then
  echo "failed stages: ${failed_stages[*]}"
  ((failed == 0)) && failed=1
fi
echo "tests: ${passed} passed, ${failed} failed"
((${#failed_stages[@]} == 0))
