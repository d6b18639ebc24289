#!/usr/bin/env bash
# Installs the Debian 12 packages wavebench needs. Idempotent: installs only what is missing.
# Usage: scripts/install-deps.sh [--main] [--with-vm]
#   --main     only what the main job needs (build the `wavebench` CLI and run the simulated
#              bench): no test tools, no browser, no database server, no console libraries
#   --with-vm  adds what the vcan VM runner needs
set -euo pipefail

# The main job: the compilers and the libraries the CLI links.
main_packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libfftw3-dev libspdlog-dev libfmt-dev libboost-dev libboost-system-dev
  libmodbus-dev libmatio-dev libhdf5-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libsqlite3-dev libcairo2-dev libssl-dev libsodium-dev
  libpq-dev
)
# The tests on top: their frameworks, the fuzzers' clang, the independent peers and readers
# (CAN, Modbus, PostgreSQL, Octave, h5py, Chromium), packaging's sandbox.
test_packages=(
  clang-format postgresql-15
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  clang libclang-rt-14-dev
  can-utils mbpoll python3-can python3-pymodbus python3-serial-asyncio python3-scipy python3-numpy
  python3-jsonschema
  systemd python3-seccomp bubblewrap
  octave python3-h5py
  chromium chromium-driver python3-selenium poppler-utils curl
)
main_only=0
with_vm=0
for arg in "$@"; do
  case "$arg" in
    --main) main_only=1 ;;
    --with-vm) with_vm=1 ;;
    *) echo "install-deps: unknown option '$arg' (expected --main or --with-vm)" >&2; exit 2 ;;
  esac
done
packages=("${main_packages[@]}")
((main_only)) || packages+=("${test_packages[@]}")
((with_vm)) && packages+=(qemu-system-x86 busybox-static cpio kmod)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
((main_only)) || command -v npm >/dev/null || missing+=(npm)

install_front_end() {
  # The console's libraries (web/package.json), exactly as web/package-lock.json pins them.
  # Only when the lockfile changed since the last install: nothing is fetched otherwise.
  local root
  root="$(cd "$(dirname "$0")/.." && pwd)"
  if [[ ! -f "$root/web/node_modules/.package-lock.json" ||
        "$root/web/package-lock.json" -nt "$root/web/node_modules/.package-lock.json" ]]; then
    echo "install-deps: npm ci --prefix web"
    npm ci --prefix "$root/web" --no-audit --no-fund --loglevel=error >/dev/null
  fi
}

if ((${#missing[@]} == 0)); then
  ((main_only)) || install_front_end
  exit 0
fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
((main_only)) || install_front_end
