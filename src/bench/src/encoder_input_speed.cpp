#include "wavebench/bench/encoder_input_speed.hpp"

namespace wavebench::bench {

std::optional<double> EncoderInputSpeed::add(std::int64_t time_ns, double theta_out_rad) noexcept {
  if (size_ > 0) {
    const auto last = at(size_ - 1).time_ns;
    if (time_ns == last) return std::nullopt;
    if (time_ns < last) reset();
  }
  if (size_ == kCapacity) drop_oldest();
  points_[(first_ + size_) % kCapacity] = {time_ns, theta_out_rad};
  ++size_;
  // Keep the newest point that is at least a window old as the oldest one.
  while (size_ > 2 && time_ns - at(1).time_ns >= window_ns_) drop_oldest();
  const auto& oldest = at(0);
  const auto span_ns = time_ns - oldest.time_ns;
  if (size_ < 2 || span_ns < window_ns_) return std::nullopt;
  const double output_speed = (theta_out_rad - oldest.theta_out_rad) / (span_ns * 1e-9);
  return sense_.ratio * sense_.direction_sign * output_speed;
}

}  // namespace wavebench::bench
