#include "recording_clock.hpp"

#include <algorithm>

namespace wavebench::runs {

namespace {
// The plan is right within a factor of two (run_plan.cpp); its share fades as the pace becomes
// known.
constexpr double kPlanMargin = 1.1;
// Below this fraction the pace says little (run-in, the first approach).
constexpr double kPaceFrom = 0.05;
constexpr double kPaceMargin = 1.15;
}  // namespace

RecordingClock::RecordingClock(double planned_s, double wall_per_bench_s)
    : planned_s_(std::max(0.0, planned_s) * std::max(0.0, wall_per_bench_s)) {}

TimedProgress RecordingClock::at(double procedure_fraction, double elapsed_s) const {
  const double f = std::clamp(procedure_fraction, 0.0, 1.0);
  const double t = std::max(0.0, elapsed_s);
  double remaining = planned_s_ * kPlanMargin * (1 - f);
  if (f >= kPaceFrom && f < 1) remaining = std::max(remaining, kPaceMargin * t * (1 - f) / f);
  if (f >= 1) remaining = 0;
  TimedProgress p;
  p.remaining_s = remaining;
  p.fraction = t + remaining > 0 ? t / (t + remaining) : 1.0;
  return p;
}

}  // namespace wavebench::runs
