#include "recording_clock.hpp"

#include <algorithm>

namespace wavebench::procedures {

namespace {
// Before the pace is known (run-in, the first approach) the plan says what is left: it is
// right within a factor of two on a real clock (run_plan.cpp); the simulated clock runs
// faster than the plan, so there it says too much, never too little.
constexpr double kPlanMargin = 1.1;
// The pace is measured from the first report at kPaceFrom or beyond (the run-in before it
// takes no fixed share of the time: 0.3 s of a 17 s dynamic run on the simulated clock, its 5 %
// of the fraction), once kPaceSpan more of the fraction has passed.
constexpr double kPaceFrom = 0.05;
constexpr double kPaceSpan = 0.04;
// From then on the pace of the procedure's own fraction (positions, revolutions), with a
// margin for steps slower than the average so far: on the simulated bench a dynamic record
// slowed by 40-60 % once the previous run's post-run work ran beside it.
constexpr double kPaceMargin = 2.0;
// What follows the last step (the procedure's own analysis, the bench's deactivation, the
// log's close) is not in the pace: a static run's took 4-5 s on the simulated bench.
constexpr double kTailS = 6.0;
}  // namespace

RecordingClock::RecordingClock(double planned_s, double wall_per_bench_s)
    : planned_s_(std::max(0.0, planned_s) * std::max(0.0, wall_per_bench_s)) {}

TimedProgress RecordingClock::at(double procedure_fraction, double elapsed_s) {
  const double f = std::clamp(procedure_fraction, 0.0, 1.0);
  const double t = std::max(0.0, elapsed_s);
  if (!origin_ && f >= kPaceFrom) origin_ = Origin{f, t};
  const double planned = planned_s_ * kPlanMargin * (1 - f);
  double remaining = 0;
  if (f < 1) {
    remaining = planned;
    if (origin_ && f - origin_->fraction >= kPaceSpan) {
      const double pace = (t - origin_->elapsed_s) / (f - origin_->fraction);
      remaining = std::max(kPaceMargin * pace * (1 - f), std::min(kTailS, planned));
    }
  }
  TimedProgress p;
  p.remaining_s = remaining;
  p.fraction = t + remaining > 0 ? t / (t + remaining) : 1.0;
  return p;
}

}  // namespace wavebench::procedures
