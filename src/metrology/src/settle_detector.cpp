#include "wavebench/metrology/settle_detector.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wavebench::metrology {

void SettleCriteria::validate() const {
  const auto positive = [](const char* key, double v) {
    if (!(v > 0)) {
      throw std::invalid_argument(std::string("settle.") + key + " = " + std::to_string(v) +
                                  "; expected a positive value");
    }
  };
  positive("max_speed_rad_s", max_speed_rad_s);
  positive("max_drift_rad", max_drift_rad);
  positive("window_s", window_s);
  positive("max_settle_s", max_settle_s);
}

SettleDetector::SettleDetector(SettleCriteria criteria) : criteria_(criteria) {
  criteria_.validate();
}

void SettleDetector::start(double time_s) {
  window_.clear();
  started_at_ = time_s;
  state_ = SettleState::kSettling;
}

SettleState SettleDetector::add(double time_s, double theta_out_rad, double output_speed_rad_s) {
  if (state_ != SettleState::kSettling) return state_;
  // A sample too fast restarts the window: settling needs an unbroken quiet stretch.
  if (std::abs(output_speed_rad_s) > criteria_.max_speed_rad_s) {
    window_.clear();
    if (time_s - started_at_ >= criteria_.max_settle_s) state_ = SettleState::kTimedOut;
    return state_;
  }
  window_.push_back({time_s, theta_out_rad, output_speed_rad_s});
  // Keep only the samples that are needed to cover one window back from now.
  while (window_.size() > 1 && time_s - window_[1].t >= criteria_.window_s) window_.pop_front();
  const auto [lo, hi] =
      std::minmax_element(window_.begin(), window_.end(),
                          [](const Sample& a, const Sample& b) { return a.theta < b.theta; });
  if (hi->theta - lo->theta > criteria_.max_drift_rad) {
    // Drop the oldest samples until the drift fits: the quiet stretch starts after them.
    while (window_.size() > 1) {
      window_.pop_front();
      const auto [l, h] =
          std::minmax_element(window_.begin(), window_.end(),
                              [](const Sample& a, const Sample& b) { return a.theta < b.theta; });
      if (h->theta - l->theta <= criteria_.max_drift_rad) break;
    }
  }
  if (time_s - window_.front().t >= criteria_.window_s) {
    state_ = SettleState::kSettled;
    settled_at_ = time_s;
  } else if (time_s - started_at_ >= criteria_.max_settle_s) {
    state_ = SettleState::kTimedOut;
  }
  return state_;
}

}  // namespace wavebench::metrology
