#!/usr/bin/env bash
# The operator console on the simulated bench, in one command: installs what is missing,
# builds, starts wavebenchd on the in-process simulated bench and prints the console's URL and
# the token to log in with. Ctrl-C stops the daemon (the bench goes to its safe state first).
#
# Usage: scripts/console.sh [HOST:PORT]   (default 127.0.0.1:8470; runs kept in out/console/)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
listen=${1:-127.0.0.1:8470}
state=${WAVEBENCH_CONSOLE_DIR:-out/console}
mkdir -p "$state"
token_file=$state/daemon.token
wavebenchd=./${WAVEBENCH_BUILD_DIR:-build}/src/daemon/wavebenchd

"$wavebenchd" --config simulated --listen "$listen" --runs "$state/runs" --token-file "$token_file" \
  --web-root "./${WAVEBENCH_BUILD_DIR:-build}/web" &
daemon=$!
trap 'kill -TERM $daemon 2>/dev/null; wait $daemon' INT TERM EXIT
for _ in $(seq 100); do
  [[ -s "$token_file" ]] && curl -sf -o /dev/null "http://$listen/api/status" && break
  kill -0 $daemon 2>/dev/null || { echo "console: wavebenchd did not start" >&2; exit 1; }
  sleep 0.1
done
cat <<MSG

  wavebench console:  http://$listen/
  log in with the token in $token_file:
      $(cat "$token_file")
  (without logging in the console is read-only). Ctrl-C stops the daemon.

MSG
wait $daemon
