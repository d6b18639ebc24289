#include "wavebench/daemon/stated_progress.hpp"

#include <algorithm>

namespace wavebench::daemon {

namespace {
// Shown while a part runs past its estimate: "about a second", not "done".
constexpr double kOverdueRemainingS = 1.0;
}  // namespace

void StatedProgress::report(double fraction, double remaining_s, Clock::time_point at) {
  fraction_ = std::clamp(fraction, 0.0, 1.0);
  remaining_s_ = remaining_s;
  at_ = at;
}

ProgressNow StatedProgress::at(Clock::time_point now) const {
  if (remaining_s_ < 0) return {fraction_, -1};
  if (remaining_s_ == 0) return {fraction_, 0};
  const double since = std::max(0.0, std::chrono::duration<double>(now - at_).count());
  const double remaining =
      std::max(remaining_s_ - since, std::min(kOverdueRemainingS, remaining_s_));
  // The fraction moves with the clock between reports, toward 1 as the time left shrinks.
  const double fraction = 1 - (1 - fraction_) * remaining / remaining_s_;
  return {std::clamp(fraction, fraction_, 1.0), remaining};
}

}  // namespace wavebench::daemon
