#pragma once
// What a run last said about its progress, told forward to the moment /api/status asks: the
// time left counts down between reports (a static position or a twin calibration can take
// many seconds without one), and never reaches zero while the work goes on.

#include <chrono>

namespace wavebench::daemon {

struct ProgressNow {
  double fraction = 0;
  double remaining_s = -1;  // negative: not known
};

class StatedProgress {
 public:
  using Clock = std::chrono::steady_clock;
  void report(double fraction, double remaining_s, Clock::time_point at = Clock::now());
  ProgressNow at(Clock::time_point now = Clock::now()) const;

 private:
  double fraction_ = 0;
  double remaining_s_ = -1;
  Clock::time_point at_{};
};

}  // namespace wavebench::daemon
