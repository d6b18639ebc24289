#pragma once
// Input shaft angle from the drive: its position made continuous.

#include <cstdint>

#include "wavebench/bench/drive_units.hpp"

namespace wavebench::bench {

// The drive's units against the input shaft's SI units live in DriveUnits (drive_units.hpp).
using InputShaftScaling = DriveUnits;

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
