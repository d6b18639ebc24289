#!/usr/bin/env bash
# Runs the `vcan` ctest label against a real SocketCAN vcan0 inside a small qemu VM (the host
# kernel has no CAN support). Exits with ctest's exit status, 124 when the VM timed out and 125
# when the VM could not boot or run the job.
# Usage: scripts/vcan-vm/run-vcan-tests.sh BUILD_DIR [extra ctest arguments...]
# Environment:
#   WAVEBENCH_VM_TIMEOUT  hard limit for the whole VM in seconds (default 900)
#   WAVEBENCH_VM_CACHE    where the kernel/initramfs are cached (default BUILD_DIR/vcan-vm)
#   WAVEBENCH_VM_MEMORY   guest memory in MiB (default 1024)
#   WAVEBENCH_VM_SMP      guest CPUs (default 2)
#   WAVEBENCH_VM_CPU      qemu -cpu model (default max: RDRAND seeds the guest's RNG at once)
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
t_start=${EPOCHREALTIME/,/.}

die() {
  echo "vcan-vm: ERROR: $*" >&2
  exit 125
}
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

(($# >= 1)) || die "usage: run-vcan-tests.sh BUILD_DIR [ctest arguments...]"
[[ -d "$1" ]] || die "build directory '$1' does not exist (build first: scripts/build.sh)"
build=$(cd "$1" && pwd -P)
shift
[[ -f "$build/CTestTestfile.cmake" ]] ||
  die "'$build' has no CTestTestfile.cmake: not a configured build directory with tests"
[[ "$build" != / ]] || die "the build directory cannot be /"
command -v qemu-system-x86_64 >/dev/null ||
  die "qemu-system-x86_64 not found; run: scripts/install-deps.sh --with-vm"
command -v timeout >/dev/null || die "'timeout' (coreutils) not found"

timeout_s=${WAVEBENCH_VM_TIMEOUT:-900}
[[ "$timeout_s" =~ ^[0-9]+$ ]] || die "WAVEBENCH_VM_TIMEOUT='$timeout_s': expected whole seconds"
memory=${WAVEBENCH_VM_MEMORY:-1024}
[[ "$memory" =~ ^[0-9]+$ ]] || die "WAVEBENCH_VM_MEMORY='$memory': expected MiB as a number"
smp=${WAVEBENCH_VM_SMP:-2}
[[ "$smp" =~ ^[1-9][0-9]*$ ]] || die "WAVEBENCH_VM_SMP='$smp': expected a CPU count >= 1"
cpu=${WAVEBENCH_VM_CPU:-max}
[[ "$cpu" =~ ^[A-Za-z0-9_.,=+-]+$ ]] || die "WAVEBENCH_VM_CPU='$cpu': expected a qemu CPU model"
cache=${WAVEBENCH_VM_CACHE:-$build/vcan-vm}
vmdir=$build/vcan-vm
run=$vmdir/run
mkdir -p "$vmdir" "$cache"

# One VM per build directory at a time; the image cache has its own lock so that two build
# directories sharing WAVEBENCH_VM_CACHE do not build it twice.
exec 8>"$vmdir/run.lock"
flock -w "$timeout_s" 8 || die "another vcan VM run holds $vmdir/run.lock"
(
  flock -w "$timeout_s" 9 || die "another run holds $cache/image.lock"
  bash "$here/build-image.sh" "$cache"
) 9>"$cache/image.lock" || die "could not build the VM image (see above)"

rm -rf "$run"
mkdir -p "$run"
printf '%s\n' "$build" >"$run/build-dir"
# The job runs inside the chroot (as root, with the host's ctest); arguments are quoted for sh.
{
  echo '#!/bin/sh'
  echo '# Written by scripts/vcan-vm/run-vcan-tests.sh; run by the VM init inside the chroot.'
  printf 'cd %q || exit 125\n' "$build"
  printf 'exec ctest --test-dir %q -L vcan --output-on-failure' "$build"
  for arg in "$@"; do printf ' %q' "$arg"; done
  echo
} >"$run/job.sh"

security=passthrough
if [[ $(id -u) -ne 0 ]]; then
  # passthrough needs root to set owners; as a user the files simply stay the user's.
  security=none
fi

qemu=(
  qemu-system-x86_64 -accel tcg -cpu "$cpu" -smp "$smp" -m "$memory"
  -nodefaults -display none -no-reboot -serial stdio
  -kernel "$cache/kernel" -initrd "$cache/initramfs.cpio.gz"
  -append "console=ttyS0 quiet loglevel=3 panic=-1"
  -virtfs "local,path=/,mount_tag=hostroot,security_model=$security,readonly=on,multidevs=remap"
  -virtfs "local,path=${build//,/,,},mount_tag=buildshare,security_model=$security,multidevs=remap"
)

echo "vcan-vm: booting $(cat "$cache/kernel.version" 2>/dev/null || echo '?') under TCG" \
  "(timeout ${timeout_s}s) for: ctest -L vcan $*"
t_qemu=${EPOCHREALTIME/,/.}
t_boot=""
# Console lines are echoed as they come (without the serial CRs); the time the init's "booted"
# line arrives is the boot time.
exec 7>"$run/console.log"
while IFS= read -r line || [[ -n "$line" ]]; do
  line=${line%$'\r'}
  printf '%s\n' "$line"
  printf '%s\n' "$line" >&7
  if [[ -z "$t_boot" && "$line" == "vcan-vm: booted"* ]]; then
    t_boot=${EPOCHREALTIME/,/.}
  fi
done < <(
  rc=0
  timeout --kill-after=15 "$timeout_s" "${qemu[@]}" </dev/null 2>&1 || rc=$?
  echo "$rc" >"$run/qemu.status"
)
exec 7>&-
t_end=${EPOCHREALTIME/,/.}
qemu_status=$(cat "$run/qemu.status" 2>/dev/null || echo '?')

summary() {
  echo "vcan-vm: ---- ctest summary (vcan label, inside the VM) ----"
  if [[ -f "$run/ctest.log" ]]; then
    # ctest's own summary: totals, time, and the lists of failed and not-run tests (in order).
    grep -E '(tests passed|tests failed|Total Test time|No tests were found|The following tests)|^[[:space:]]+[0-9]+ - .+ \([A-Za-z_ ]+\)$' \
      "$run/ctest.log" || true
  else
    echo "(no ctest output)"
  fi
  echo "vcan-vm: boot ${1}s, tests ${2}s, total runner $(elapsed "$t_start" "$t_end")s" \
    "(logs: $run/console.log, $run/ctest.log)"
}

if [[ -z "$t_boot" ]]; then
  if [[ "$qemu_status" == 124 || "$qemu_status" == 137 ]]; then
    echo "vcan-vm: ERROR: the VM did not finish booting within ${timeout_s}s (see $run/console.log)" >&2
    exit 124
  fi
  echo "vcan-vm: ERROR: the VM failed to boot (qemu exit ${qemu_status:-?});" \
    "console output is in $run/console.log" >&2
  exit 125
fi
boot_s=$(elapsed "$t_qemu" "$t_boot")
tests_s=$(elapsed "$t_boot" "$t_end")
if [[ ! -f "$run/status" ]]; then
  summary "$boot_s" "$tests_s"
  if [[ "$qemu_status" == 124 || "$qemu_status" == 137 ]]; then
    echo "vcan-vm: ERROR: timed out after ${timeout_s}s while running the tests" >&2
    exit 124
  fi
  echo "vcan-vm: ERROR: the VM stopped before the tests reported a status (qemu exit" \
    "${qemu_status:-?}); see $run/console.log" >&2
  exit 125
fi
status=$(cat "$run/status")
[[ "$status" =~ ^[0-9]+$ ]] || status=125
summary "$boot_s" "$tests_s"
echo "vcan-vm: ctest exit status $status"
exit "$status"
