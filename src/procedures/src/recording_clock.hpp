#pragma once
#include <optional>

// The recording's progress by time, not by step: a static run's positions or a dynamic run's
// revolutions do not take equal shares of its duration (run-in, approaches, the procedure's
// own analysis). From the plan's estimate (run_plan.hpp) before the pace is known, then from
// the pace of the procedure's own fraction; the larger of the two, so that the time left is
// not promised short (issue #21: never less than the true remaining time by more than 20 %).

namespace wavebench::procedures {

struct TimedProgress {
  double fraction = 0;     // elapsed / (elapsed + remaining)
  double remaining_s = 0;  // wall seconds
};

class RecordingClock {
 public:
  // `planned_s`: the plan's bench time (RunEstimate::bench_time_s); `wall_per_bench_s`: wall
  // seconds per bench second (1 on a real clock; measured for the simulated one).
  explicit RecordingClock(double planned_s, double wall_per_bench_s = 1.0);
  // `procedure_fraction`: what the procedure reported (0..1); `elapsed_s`: wall seconds since
  // the recording started.
  TimedProgress at(double procedure_fraction, double elapsed_s);

 private:
  struct Origin {
    double fraction, elapsed_s;
  };
  double planned_s_;
  std::optional<Origin> origin_;  // where the pace is measured from
};

}  // namespace wavebench::procedures
