#pragma once
// What one SYNC cycle gathers: the sample (channel-keyed through the bench's channel table) and
// the drive values the safety checks need beside it.

#include <cstddef>
#include <cstdint>

#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::bench {

// A channel's place in the bench's channel table: the core channels in storage::kCoreChannels
// order, then the extra ones (SyncSample::extra) in config order.
struct ChannelSlot {
  std::size_t index = 0;
  static constexpr std::size_t kCore = storage::kCoreChannelCount;
  static ChannelSlot extra(std::size_t i) { return {kCore + i}; }
  bool operator==(const ChannelSlot&) const = default;
};

// The core slots by name, as storage::kCoreChannels lists them.
namespace slot {
inline constexpr ChannelSlot kThetaIn{storage::channel::kThetaIn},
    kThetaOut{storage::channel::kThetaOut}, kInputSpeed{storage::channel::kInputSpeed},
    kTorque{storage::channel::kTorque}, kBrakeCurrent{storage::channel::kBrakeCurrent},
    kBrakeTorque{storage::channel::kBrakeTorque};
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

  // Writes a channel's value and marks it arrived in this cycle; a slot past the sample's
  // channels is dropped (the bench's channel table was checked against them at start).
  void set(ChannelSlot at, double value) noexcept { sample.set(at.index, value); }
};

}  // namespace wavebench::bench
