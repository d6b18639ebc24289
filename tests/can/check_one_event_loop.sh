#!/usr/bin/env bash
# Issue 23: one event loop. Fails when product code under ROOT (src/, sim/, drivers/) runs, polls
# or restarts an io_context anywhere but the one loop's file. The CLI tools' own `io.run()` (no
# other loop runs there) and the daemon's thread loops are `.run()`, which this does not match.
set -euo pipefail
root="${1:?usage: check_one_event_loop.sh SOURCE_ROOT}"
the_loop="drivers/can/src/event_loop.cpp"
cd "$root"
dirs=()
for d in src sim drivers; do [[ -d $d ]] && dirs+=("$d"); done
pattern='\.(run_one|run_one_for|run_one_until|run_for|run_until|poll_one|restart)\(|\.poll\(\)'
found=$(grep -rnE --include='*.cpp' --include='*.hpp' --include='*.h' "$pattern" "${dirs[@]}" |
  grep -v "^${the_loop}:" || true)
if [[ -n $found ]]; then
  echo "io_context pumped outside the one event loop (${the_loop}); wait with" >&2
  echo "wavebench/can/event_loop.hpp or suspend on an asynchronous call instead:" >&2
  echo "$found" >&2
  exit 1
fi
echo "one event loop: no pump outside ${the_loop}"
