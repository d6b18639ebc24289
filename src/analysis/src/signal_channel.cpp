#include "wavebench/analysis/signal_channel.hpp"

#include <cmath>
#include <numeric>
#include <stdexcept>

namespace wavebench::analysis {

std::vector<std::string> response_channel_names() {
  return {"theta1",     "omega1", "theta2_dev",  "omega2",      "alpha2",      "twist",
          "twist_rate", "te",     "gear_torque", "load_torque", "motor_torque"};
}

std::span<const double> response_channel(const model::SampledResponse& r, const std::string& name) {
  if (name == "theta1") return r.theta1;
  if (name == "omega1") return r.omega1;
  if (name == "theta2_dev") return r.theta2_dev;
  if (name == "omega2") return r.omega2;
  if (name == "alpha2") return r.alpha2;
  if (name == "twist") return r.twist;
  if (name == "twist_rate") return r.twist_rate;
  if (name == "te") return r.te;
  if (name == "gear_torque") return r.gear_torque;
  if (name == "load_torque") return r.load_torque;
  if (name == "motor_torque") return r.motor_torque;
  std::string expected;
  for (const auto& n : response_channel_names()) expected += (expected.empty() ? "" : ", ") + n;
  throw std::invalid_argument("analysis.spectrum.signal = '" + name + "': expected one of " +
                              expected);
}

double mean_of(std::span<const double> values) {
  if (values.empty()) return 0;
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

double rms_about_mean(std::span<const double> values) {
  if (values.empty()) return 0;
  const double mean = mean_of(values);
  double sum = 0;
  for (double v : values) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / static_cast<double>(values.size()));
}

}  // namespace wavebench::analysis
