#pragma once
// The one place where the drive's units become SI: motor encoder increments (0x6064, 0x607A,
// 0x60F4) to input angle [rad], increments/s (0x606C, 0x60FF, 0x6081) to rad/s.

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace wavebench::bench {

class InputShaftScaling {
 public:
  explicit InputShaftScaling(std::uint32_t counts_per_revolution)
      : counts_per_rad_(counts_per_revolution / (2 * std::numbers::pi)) {}

  double angle(double counts) const noexcept { return counts / counts_per_rad_; }
  double speed(double counts_per_s) const noexcept { return counts_per_s / counts_per_rad_; }
  double counts_per_rad() const noexcept { return counts_per_rad_; }

  // Throws std::invalid_argument naming `what` when the value does not fit the drive's INTEGER32.
  std::int32_t position_counts(double rad, const char* what) const {
    return to_i32(rad * counts_per_rad_, what, rad, "rad");
  }
  std::int32_t velocity_counts(double rad_s, const char* what) const {
    return to_i32(rad_s * counts_per_rad_, what, rad_s, "rad/s");
  }

 private:
  static std::int32_t to_i32(double counts, const char* what, double value, const char* unit) {
    const double r = std::round(counts);
    if (!std::isfinite(r) || r > std::numeric_limits<std::int32_t>::max() ||
        r < std::numeric_limits<std::int32_t>::min()) {
      throw std::invalid_argument(std::string(what) + " = " + std::to_string(value) + " " + unit +
                                  ": outside the drive's 32-bit range");
    }
    return static_cast<std::int32_t>(r);
  }
  double counts_per_rad_;
};

// A drive position (INTEGER32, may wrap) made continuous.
class Int32Unwrapper {
 public:
  std::int64_t update(std::int32_t raw) noexcept {
    if (have_) {
      const auto delta = static_cast<std::int32_t>(static_cast<std::uint32_t>(raw) -
                                                   static_cast<std::uint32_t>(last_));
      value_ += delta;
    } else {
      value_ = raw;
      have_ = true;
    }
    last_ = raw;
    return value_;
  }

 private:
  bool have_ = false;
  std::int32_t last_ = 0;
  std::int64_t value_ = 0;
};

}  // namespace wavebench::bench
