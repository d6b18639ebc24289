#!/usr/bin/env bash
# The main job: installs what is missing, builds, then runs the simulated bench (in process, on
# its simulated clock, with the twin beside it): static TE, dynamic TE and lost motion. Each run
# gets its folder under out/bench/ (samples.wbs, results.json, twin.csv, report.html and plots);
# the session's index.html gathers them. Prints the summary table and where the report is, then
# runs the twin's reference case (XB-80-134H) into out/xb-80-134h/.
#
# Usage: scripts/run-main.sh [OUT_DIR]   (default out/bench; WAVEBENCH_SKIP_TWIN_CASE=1 skips
# the XB-80 case)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --main
bash scripts/build.sh --main
wavebench=./${WAVEBENCH_BUILD_DIR:-build}/src/cli/wavebench
out=${1:-out/bench}
mkdir -p "$out"

# The run folders under $out, one a line. A run's folder is the one that is new after it, so
# runs left there by earlier sessions stay out of this session's index.
run_folders() { find "$out" -mindepth 1 -maxdepth 1 -type d -name '[0-9]*' | sort; }

runs=()
for procedure in static dynamic lost-motion; do
  echo "== wavebench run $procedure --bench simulated --out $out"
  before=$(run_folders)
  status=0
  "$wavebench" run "$procedure" --bench simulated --out "$out" || status=$?
  new=$(comm -13 <(echo "$before") <(run_folders))
  if [[ -z "$new" ]]; then
    echo "run-main: wavebench run $procedure wrote no run folder (exit $status)" >&2
    exit 1
  fi
  while IFS= read -r dir; do runs+=("$dir"); done <<<"$new"
  # An aborted run keeps its data and is reported; the job goes on to the next procedure.
  ((status == 0)) || echo "run-main: $procedure exited with $status; its report says why" >&2
done

echo
echo "== session report"
"$wavebench" report "${runs[@]}"

if [[ "${WAVEBENCH_SKIP_TWIN_CASE:-0}" != 1 ]]; then
  echo
  echo "== the twin's reference case (XB-80-134H)"
  "$wavebench" twin configs/twin/xb-80-134h.yaml --out out/xb-80-134h --quiet
  echo "twin case: out/xb-80-134h/"
fi
echo
echo "report: $out/index.html"
