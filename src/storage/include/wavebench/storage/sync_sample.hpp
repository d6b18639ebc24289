#pragma once
// One SYNC cycle of the bench (bench.md §1): the values that followed one SYNC, with the
// receive timestamp and SYNC counter kept so that spectra never assume a uniform period.
//
// kCoreChannels below is the one table of the six channels every sample has: the sample log,
// its CSV and exports, the API's JSON, the run trace and the acquisition all iterate it, so a
// channel is named, placed and validated here only.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace wavebench::storage {

// Bits of SyncSample::flags. A channel whose value did not arrive in the cycle has its bit
// clear; the value is then whatever the acquisition left there and must not be used. The six
// channel bits are the core channels' positions in kCoreChannels (bit i: channel i).
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

// Channels a bench config adds beyond the core ones (an input-side encoder, a second torque
// sensor...), by position in the bench's channel list; the sample log's header names them.
inline constexpr std::size_t kMaxExtraChannels = 8;
inline constexpr std::size_t kCoreChannelCount = 6;
// Channel positions of a sample: the core ones in kCoreChannels order, then the extra ones.
inline constexpr std::size_t kMaxChannels = kCoreChannelCount + kMaxExtraChannels;

struct SyncSample;

// A core channel: everything every reader and writer of samples needs to know about it.
struct CoreChannel {
  std::string_view name;      // sample log header, exports, /api/channels, run trace
  std::string_view unit;      // SI, as the sample log header states it
  std::string_view column;    // CSV column and JSON key (name and unit in one word)
  std::size_t record_offset;  // byte offset of its f64 in a sample log record
  SampleFlag valid;           // its bit of SyncSample::flags
  double SyncSample::*value;  // where a sample holds it
};

struct SyncSample {
  std::uint64_t index = 0;         // position in the log, assigned on append
  std::uint32_t sync_counter = 0;  // as received (CiA 301 0x1019 counter, 1..overflow)
  std::uint32_t flags = 0;         // SampleFlag bits
  std::int64_t receive_time_ns = 0;
  // The core values, in kCoreChannels order; named because the procedures need each by name.
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

  // By channel position (core ones, then extra ones; see kMaxChannels): what the tables
  // iterate. Positions past kMaxChannels read as not arrived and are not written.
  bool arrived(std::size_t channel) const;
  double value(std::size_t channel) const;
  void set(std::size_t channel, double v) noexcept;  // the value, and marks it arrived
  void clear(std::size_t channel) noexcept;          // marks it not arrived
};

// The core channels, in sample log and SyncSample order. Byte offsets are those of the sample
// log's record (docs in sample_log.hpp), which existing run folders hold: never reorder.
inline constexpr std::array<CoreChannel, kCoreChannelCount> kCoreChannels{{
    {"theta_in", "rad", "theta_in_rad", 24, kThetaInValid, &SyncSample::theta_in_rad},
    {"theta_out", "rad", "theta_out_rad", 32, kThetaOutValid, &SyncSample::theta_out_rad},
    {"input_speed", "rad/s", "input_speed_rad_s", 40, kInputSpeedValid,
     &SyncSample::input_speed_rad_s},
    {"torque", "N*m", "torque_nm", 48, kTorqueValid, &SyncSample::torque_nm},
    {"brake_current", "A", "brake_current_a", 56, kBrakeCurrentValid, &SyncSample::brake_current_a},
    {"brake_torque", "N*m", "brake_torque_nm", 64, kBrakeTorqueValid, &SyncSample::brake_torque_nm},
}};

// Channel positions of the core channels by name, for code that needs one channel.
namespace channel {
inline constexpr std::size_t kThetaIn = 0, kThetaOut = 1, kInputSpeed = 2, kTorque = 3,
                             kBrakeCurrent = 4, kBrakeTorque = 5;
}

// The table's own consistency, checked where it is written.
consteval bool core_channels_consistent() {
  std::uint32_t bits = 0;
  for (std::size_t i = 0; i < kCoreChannels.size(); ++i) {
    const auto& c = kCoreChannels[i];
    if (c.valid != (1u << i)) return false;           // bit i: channel i
    if (c.record_offset != 24 + 8 * i) return false;  // contiguous f64s after the time
    if (c.name.empty() || c.name.size() > 31 || c.unit.empty() || c.unit.size() > 15) return false;
    bits |= c.valid;
  }
  return bits == kAllChannelsValid;
}
static_assert(core_channels_consistent(), "kCoreChannels: bits, offsets or name sizes");

inline bool SyncSample::arrived(std::size_t channel) const {
  if (channel < kCoreChannelCount) return valid(kCoreChannels[channel].valid);
  return channel < kMaxChannels && extra_arrived(channel - kCoreChannelCount);
}

inline double SyncSample::value(std::size_t channel) const {
  if (channel < kCoreChannelCount) return this->*kCoreChannels[channel].value;
  return channel < kMaxChannels ? extra[channel - kCoreChannelCount] : 0.0;
}

inline void SyncSample::set(std::size_t channel, double v) noexcept {
  if (channel < kCoreChannelCount) {
    this->*kCoreChannels[channel].value = v;
    flags |= kCoreChannels[channel].valid;
  } else if (channel < kMaxChannels) {
    extra[channel - kCoreChannelCount] = v;
    extra_valid |= 1U << (channel - kCoreChannelCount);
  }
}

inline void SyncSample::clear(std::size_t channel) noexcept {
  if (channel < kCoreChannelCount)
    flags &= ~static_cast<std::uint32_t>(kCoreChannels[channel].valid);
  else if (channel < kMaxChannels)
    extra_valid &= ~(1U << (channel - kCoreChannelCount));
}

}  // namespace wavebench::storage
