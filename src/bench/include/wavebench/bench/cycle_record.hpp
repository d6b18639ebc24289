#pragma once
// What one SYNC cycle gathers: the sample (channel-keyed through the bench's channel table) and
// the drive values the safety checks need beside it.

#include <cstddef>
#include <cstdint>

#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::bench {

// A channel's place in the bench's channel table: the six core channels in
// storage::core_channels() order, then the extra ones (SyncSample::extra) in config order.
struct ChannelSlot {
  std::size_t index = 0;
  static constexpr std::size_t kCore = 6;
  static ChannelSlot extra(std::size_t i) { return {kCore + i}; }
  bool operator==(const ChannelSlot&) const = default;
};

// The core slots by name, as storage::core_channels() lists them.
namespace slot {
inline constexpr ChannelSlot kThetaIn{0}, kThetaOut{1}, kInputSpeed{2}, kTorque{3},
    kBrakeCurrent{4}, kBrakeTorque{5};
}

// Drive values of the cycle that are not channels of the sample but the safety checks need.
struct DriveCycleValues {
  bool status_valid = false;
  std::uint16_t statusword = 0;
  bool following_error_valid = false;
  double following_error_rad = 0;
};

struct CycleRecord {
  storage::SyncSample sample;
  DriveCycleValues drive;

  // Writes a channel's value and marks it arrived in this cycle.
  void set(ChannelSlot at, double value) noexcept {
    auto& s = sample;
    switch (at.index) {
      case 0:
        s.theta_in_rad = value;
        s.flags |= storage::kThetaInValid;
        return;
      case 1:
        s.theta_out_rad = value;
        s.flags |= storage::kThetaOutValid;
        return;
      case 2:
        s.input_speed_rad_s = value;
        s.flags |= storage::kInputSpeedValid;
        return;
      case 3:
        s.torque_nm = value;
        s.flags |= storage::kTorqueValid;
        return;
      case 4:
        s.brake_current_a = value;
        s.flags |= storage::kBrakeCurrentValid;
        return;
      case 5:
        s.brake_torque_nm = value;
        s.flags |= storage::kBrakeTorqueValid;
        return;
      default:
        break;
    }
    const std::size_t i = at.index - ChannelSlot::kCore;
    if (i >= storage::kMaxExtraChannels) return;
    s.extra[i] = value;
    s.extra_valid |= 1U << i;
  }
};

}  // namespace wavebench::bench
