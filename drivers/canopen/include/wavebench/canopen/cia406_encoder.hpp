#pragma once
// CiA 406 rotary encoder client: resolution and turn count from the device (0x6501/0x6502, or
// configured), the device type (0x1000: 0x10196 single-turn, 0x20196 multi-turn), and the
// position value 0x6004 unwrapped across the encoder's own wrap into a continuous angle.

#include <cstdint>
#include <optional>
#include <system_error>

#include "wavebench/canopen/sdo_client.hpp"
#include "wavebench/canopen/used_object.hpp"

namespace wavebench::canopen {

struct Cia406Config {
  std::optional<std::uint32_t> counts_per_turn;  // overrides 0x6501
  std::optional<std::uint32_t> turns;            // overrides 0x6502 (1 for single-turn)
};

inline constexpr std::uint32_t kCia406SingleTurn = 0x00010196;
inline constexpr std::uint32_t kCia406MultiTurn = 0x00020196;

class PositionUnwrapper {
 public:
  // `range` is the raw value count before the encoder wraps (counts/turn × turns); 0 = 2^32.
  explicit PositionUnwrapper(std::uint64_t range) noexcept
      : range_(range == 0 ? 1ULL << 32 : range) {}
  // Continuous position in counts; the first sample defines the origin's turn.
  std::int64_t update(std::uint32_t raw) noexcept;
  void reset() noexcept { have_ = false; }
  std::int64_t wraps() const noexcept { return wraps_; }

 private:
  std::uint64_t range_;
  bool have_ = false;
  std::uint32_t last_ = 0;
  std::int64_t wraps_ = 0;
};

class Cia406Encoder {
 public:
  Cia406Encoder(SdoClient& sdo, Cia406Config config = {});
  Cia406Encoder(const Cia406Encoder&) = delete;
  Cia406Encoder& operator=(const Cia406Encoder&) = delete;

  // Every object the bench uses on a CiA 406 encoder (SDO and its TPDO1 mapping).
  static std::span<const UsedObject> used_objects() noexcept;

  // Reads 0x1000 and, unless configured, 0x6501 and 0x6502. Throws naming the object.
  void read_configuration();
  void read_configuration(std::error_code& ec) noexcept;

  std::uint32_t device_type() const noexcept { return device_type_; }
  bool multi_turn() const noexcept { return (device_type_ & 0xFFFF0000U) == 0x00020000U; }
  std::uint32_t counts_per_turn() const noexcept { return counts_per_turn_; }
  std::uint32_t turns() const noexcept { return turns_; }

  // From a TPDO (0x6004 mapped) or an SDO read: the continuous angle [rad].
  double on_position(std::uint32_t raw) noexcept;
  double read_angle();          // by SDO
  std::uint16_t read_alarms();  // 0x6503
  double angle() const noexcept { return angle_; }

 private:
  SdoClient& sdo_;
  Cia406Config config_;
  std::uint32_t device_type_ = 0;
  std::uint32_t counts_per_turn_ = 0;
  std::uint32_t turns_ = 1;
  PositionUnwrapper unwrapper_{0};
  double angle_ = 0;
};

}  // namespace wavebench::canopen
