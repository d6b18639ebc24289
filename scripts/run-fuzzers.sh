#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan, whole tree instrumented) and runs each
# for a bounded time. Usage: scripts/run-fuzzers.sh [seconds per target, default 30] [STAGE]
# STAGE: all (default), build or run. run-tests.sh builds first, then runs the fuzzers (one
# core) beside the vcan VM (one TCG thread).
# -O1 and line tables: libFuzzer's own advice for speed of both the build and the search;
# sanitizer reports still name file and line.
set -euo pipefail
seconds="${1:-30}"
stage="${2:-all}"
case "$stage" in
  all | build | run) ;;
  *) echo "run-fuzzers.sh: stage '$stage': expected all, build or run" >&2; exit 2 ;;
esac
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${WAVEBENCH_FUZZ_BUILD_DIR:-$root/build-fuzz}"
jobs="${WAVEBENCH_JOBS:-2}"

targets=(fuzz_can_frames fuzz_sdo_client fuzz_eds fuzz_twin_config fuzz_bench_config
  fuzz_procedure_options fuzz_brake_config fuzz_simbench_config fuzz_http_api fuzz_exports)
if [[ "$stage" != run ]]; then
  cmake -S "$root" -B "$build" -G Ninja \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DCMAKE_C_FLAGS="-fsanitize=fuzzer-no-link,address,undefined" \
    -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined" \
    -DWAVEBENCH_BUILD_FUZZERS=ON -DWAVEBENCH_BUILD_TESTS=OFF -DWAVEBENCH_BUILD_BENCHMARKS=OFF \
    -DWAVEBENCH_BUILD_CONSOLE=OFF -DWAVEBENCH_WERROR=OFF >/dev/null
  cmake --build "$build" -j "$jobs" --target "${targets[@]}"
fi
[[ "$stage" != build ]] || exit 0

status=0
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"
  mkdir -p "$corpus"
  # Config fuzzers start from the shipped configs, copied fresh (never committed as corpora).
  case "$t" in
    fuzz_eds) cp -n "$root"/configs/eds/*.eds "$corpus/" ;;
    fuzz_twin_config) cp -n "$root"/configs/twin/*.yaml "$corpus/" ;;
    fuzz_bench_config) cp -n "$root"/configs/benches/*.yaml "$corpus/" ;;
    fuzz_simbench_config) # the example of simulated_bench_config.hpp
      sed -n 's|^//   ||; s|^//$||; /^simbench:/,/^$/p' \
        "$root"/sim/devices/canopen/include/wavebench/simdevices/simulated_bench_config.hpp \
        >"$corpus/example.yaml" ;;
    fuzz_procedure_options) cp -n "$root"/configs/procedures/*.yaml "$corpus/" ;;
    fuzz_brake_config) cp -n "$root"/configs/bench/*.yaml "$corpus/" ;;
    fuzz_http_api) bash "$root"/fuzz/http_seeds.sh "$corpus" ;;
    fuzz_exports) # each format, a few sizes, a disk that fills up at once or never
      for f in 0 1 2 3; do
        printf "\\x0$f\\xff\\xff\\xff\\x01\\x00\\x01%8s\\x00{\"a\":1}" "" >"$corpus/seed-$f-full"
        printf "\\x0$f\\x00\\x10\\x00\\x10\\x00\\x02%8s\\x01[1,2]" "" >"$corpus/seed-$f-cut"
      done ;;
  esac
  echo "== $t for ${seconds}s"
  # -timeout: any single input taking over 10 s counts as a hang.
  lsan="$root/fuzz/$t.lsan.supp"
  [[ -f "$lsan" ]] || lsan=/dev/null
  if ! LSAN_OPTIONS="suppressions=$lsan" "$build/fuzz/$t" -max_total_time="$seconds" -timeout=10 \
       -rss_limit_mb=2048 -print_final_stats=1 "$corpus" 2>"$build/$t.log"; then
    echo "!! $t failed; see $build/$t.log"
    tail -n 40 "$build/$t.log"
    status=1
  else
    grep -E 'stat::number_of_executed_units|Done' "$build/$t.log" | tail -n 2 || true
  fi
done
exit "$status"
