#pragma once
// The input speed as the output encoder measures it (issue #20): the output's angle change over
// a short window of bench time, × N and the gear's sense (θ_in ≈ N·s·θ_out). No drive unit
// enters it, so a drive whose velocity unit differs from the config cannot blind it.
//
// The window (8 ms by default) is what quantisation needs: a ~1M counts/turn output encoder
// differenced over one 1 ms cycle reads ±6 rpm at the input (×100); over 8 ms it reads < 1 rpm,
// and a backlash jump of a few arcmin (the output moving with no input motion) reads a few
// hundred rpm at most, far below an input speed limit of thousands. θ_out is unwrapped by the
// encoder device, so differences never see the encoder's own wrap.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "wavebench/model/gear_sense.hpp"

namespace wavebench::bench {

class EncoderInputSpeed {
 public:
  explicit EncoderInputSpeed(model::GearSense sense, double window_s = 8e-3)
      : sense_(sense), window_ns_(static_cast<std::int64_t>(window_s * 1e9)) {}

  // One valid output angle [rad, unwrapped] at bench time `time_ns`. Returns the input speed
  // [rad/s] over the last window once a window of samples is held; a sample whose time does not
  // advance is ignored, one going back in time starts afresh.
  std::optional<double> add(std::int64_t time_ns, double theta_out_rad) noexcept;
  void reset() noexcept { size_ = 0; }

 private:
  struct Point {
    std::int64_t time_ns;
    double theta_out_rad;
  };
  // Holds a window at SYNC periods down to window / (kCapacity - 1); at shorter periods the
  // oldest point is dropped and the window shrinks to kCapacity - 1 periods.
  static constexpr std::size_t kCapacity = 64;

  const Point& at(std::size_t i) const noexcept { return points_[(first_ + i) % kCapacity]; }
  void drop_oldest() noexcept {
    first_ = (first_ + 1) % kCapacity;
    --size_;
  }

  model::GearSense sense_;
  std::int64_t window_ns_;
  std::array<Point, kCapacity> points_{};
  std::size_t first_ = 0;
  std::size_t size_ = 0;
};

}  // namespace wavebench::bench
