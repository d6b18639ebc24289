#pragma once
// The post-run stages of a run (recorded_run.hpp), each a function of the run's context so
// that each can be run and tested alone, in the order post_run_stages() lists them. None calls
// the bench. Each has an estimate of its wall time from what is known before it runs (the
// record's length, the unit's earlier records), so that progress can say what is left.

#include <span>

#include "run_context.hpp"

namespace wavebench::procedures {

struct PostRunStage {
  const char* phase;                        // as /api/status shows it
  double (*estimate_s)(const RunContext&);  // wall seconds, with a margin; 0 when skipped
  void (*run)(RunContext&);
};

std::span<const PostRunStage> post_run_stages();

// results.json at the recording's end: "status": "processing" (the index row stays
// `running`), so that the run folder says where the run is.
void mark_processing(RunContext& c);

void finish_twin(RunContext& c);       // the twin beside the bench drained, its residual
void calibrate_twin(RunContext& c);    // the twin fitted to this run (complete runs)
void decide_verdict(RunContext& c);    // status, limit checks, pass and verdict in results
void write_results(RunContext& c);     // results.json, status.json as it will be recorded
void write_report(RunContext& c);      // report.html and its plots
void record_end(RunContext& c);        // results.json final, then the index row finished
void update_unit_twin(RunContext& c);  // the unit's twin over its newest runs

}  // namespace wavebench::procedures
