#!/usr/bin/env bash
# All tests: installs what is missing (the vcan VM's packages too), builds with warnings as
# errors, runs the unit and integration suites with ctest, then builds the fuzzers and runs
# them for a bounded time while the vcan suite runs inside a small VM. Every stage runs; the
# exit status is non-zero if any failed. The last line sums the ctest counts of both suites
# (each counted once).
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

# The fuzzers (one core each, one after the other) and the vcan VM (one TCG thread) each keep
# one core busy: after the fuzzers' build (both cores) they run side by side. The VM's output
# goes to its own log and is printed whole once it ends, not interleaved with the fuzzers'.
fuzz_seconds="${WAVEBENCH_FUZZ_SECONDS:-30}"
echo "== fuzzers: build"
bash scripts/run-fuzzers.sh "$fuzz_seconds" build 2>&1 | tee "$logs/fuzz.log"
fuzz_built=${PIPESTATUS[0]}

echo "== vcan tests (inside the VM, beside the fuzzers; printed when done, log: $logs/vcan.log)"
bash scripts/vcan-vm/run-vcan-tests.sh build >"$logs/vcan.log" 2>&1 </dev/null &
vm_pid=$!

echo "== fuzzers (${fuzz_seconds} s each)"
if ((fuzz_built == 0)); then
  bash scripts/run-fuzzers.sh "$fuzz_seconds" run 2>&1 | tee -a "$logs/fuzz.log"
  [[ ${PIPESTATUS[0]} -eq 0 ]] || failed_stages+=(fuzz)
else
  echo "!! the fuzzers did not build; see above"
  failed_stages+=(fuzz)
fi

wait "$vm_pid"
vm_status=$?
echo "== vcan tests (inside the VM): its output"
cat "$logs/vcan.log"
((vm_status == 0)) || failed_stages+=(vcan)

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
