#pragma once
// One SYNC cycle of the bench (bench.md §1): the values that followed one SYNC, with the
// receive timestamp and SYNC counter kept so that spectra never assume a uniform period.

#include <array>
#include <cstddef>
#include <cstdint>

namespace wavebench::storage {

// Bits of SyncSample::flags. A channel whose value did not arrive in the cycle has its bit
// clear; the value is then whatever the acquisition left there and must not be used.
enum SampleFlag : std::uint32_t {
  kThetaInValid = 1u << 0,
  kThetaOutValid = 1u << 1,
  kInputSpeedValid = 1u << 2,
  kTorqueValid = 1u << 3,
  kBrakeCurrentValid = 1u << 4,
  kBrakeTorqueValid = 1u << 5,
  kAllChannelsValid = (1u << 6) - 1,
  // Set by the gap counter: SYNC cycles were missed just before this sample.
  kGapBefore = 1u << 16,
  // Set by the gap counter: the counter repeated or left its configured range.
  kCounterAnomaly = 1u << 17,
};

// Channels a bench config adds beyond the six above (an input-side encoder, a second torque
// sensor...), by position in the bench's channel list; the sample log's header names them.
inline constexpr std::size_t kMaxExtraChannels = 8;

struct SyncSample {
  std::uint64_t index = 0;         // position in the log, assigned on append
  std::uint32_t sync_counter = 0;  // as received (CiA 301 0x1019 counter, 1..overflow)
  std::uint32_t flags = 0;         // SampleFlag bits
  std::int64_t receive_time_ns = 0;
  double theta_in_rad = 0;   // unwrapped
  double theta_out_rad = 0;  // unwrapped
  double input_speed_rad_s = 0;
  double torque_nm = 0;
  double brake_current_a = 0;
  double brake_torque_nm = 0;
  std::uint32_t missed_before = 0;  // SYNC cycles missed between the previous sample and this
  std::array<double, kMaxExtraChannels> extra{};  // the bench's extra channels, SI
  std::uint32_t extra_valid = 0;                  // bit i: extra[i] arrived in this cycle

  bool valid(SampleFlag channel) const { return (flags & channel) != 0; }
  bool extra_arrived(std::size_t i) const {
    return i < kMaxExtraChannels && (extra_valid >> i) & 1U;
  }
  bool complete() const { return (flags & kAllChannelsValid) == kAllChannelsValid; }
};

}  // namespace wavebench::storage
