#pragma once
// Decides when a static-TE position has settled (bench.md §4): the output speed and the drift
// of the output angle stay under thresholds over a whole window of real time, or the maximum
// settle time runs out. Fed sample by sample with the samples' own timestamps.

#include <deque>

namespace wavebench::metrology {

struct SettleCriteria {
  double max_speed_rad_s = 1e-4;  // |output speed| at every sample of the window
  double max_drift_rad = 2e-6;    // max − min of the output angle over the window
  double window_s = 0.2;          // how long both must hold
  double max_settle_s = 5.0;      // give up after this long from start()
  // Throws std::invalid_argument naming the key when a value is not positive.
  void validate() const;
};

enum class SettleState { kSettling, kSettled, kTimedOut };

class SettleDetector {
 public:
  explicit SettleDetector(SettleCriteria criteria);
  void start(double time_s);  // the move's target was reached
  SettleState add(double time_s, double theta_out_rad, double output_speed_rad_s);
  SettleState state() const { return state_; }
  double settle_time_s() const { return settled_at_ - started_at_; }  // valid when settled

 private:
  struct Sample {
    double t, theta, speed;
  };
  SettleCriteria criteria_;
  std::deque<Sample> window_;
  double started_at_ = 0;
  double settled_at_ = 0;
  SettleState state_ = SettleState::kSettling;
};

}  // namespace wavebench::metrology
