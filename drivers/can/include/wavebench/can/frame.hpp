#pragma once
// A classic CAN 2.0 frame as the bus delivers it, with its receive timestamp.

#include <array>
#include <chrono>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace wavebench::can {

// Flag bits in the "raw" identifier, identical to Linux's CAN_EFF_FLAG / CAN_RTR_FLAG /
// CAN_ERR_FLAG so that filters mean the same on the virtual bus and on SocketCAN.
inline constexpr std::uint32_t kExtendedFlag = 0x80000000U;
inline constexpr std::uint32_t kRtrFlag = 0x40000000U;
inline constexpr std::uint32_t kErrorFlag = 0x20000000U;
inline constexpr std::uint32_t kStandardIdMask = 0x000007FFU;
inline constexpr std::uint32_t kExtendedIdMask = 0x1FFFFFFFU;
inline constexpr std::size_t kMaxDataLength = 8;

struct Frame {
  std::uint32_t id = 0;  // 11-bit, or 29-bit when `extended`; error class bits for error frames
  bool extended = false;
  bool rtr = false;
  bool error = false;    // a controller error frame (Linux CAN_ERR_FLAG), not bus traffic
  std::uint8_t len = 0;  // data length code, 0..8 (an RTR frame's requested length)
  std::array<std::uint8_t, kMaxDataLength> data{};
  // Receive time on the system (realtime) clock: SocketCAN's kernel stamp, or the virtual
  // bus's delivery time. Zero for frames built locally.
  std::chrono::system_clock::time_point timestamp{};

  static Frame make(std::uint32_t id, std::initializer_list<std::uint8_t> bytes);
  static Frame make(std::uint32_t id, std::span<const std::uint8_t> bytes);

  std::span<const std::uint8_t> payload() const noexcept { return {data.data(), len}; }
  // The identifier with the Linux flag bits, as filters see it.
  std::uint32_t raw_id() const noexcept;

  // Equal on the wire: identifier, flags, length and the used data bytes; never the timestamp.
  friend bool operator==(const Frame& a, const Frame& b) noexcept;
};

// candump's compact form: "601#4018100100000000", "12345678#..", "123#R", "123#R4".
std::string to_string(const Frame& frame);
// cansend's input syntax (the inverse of to_string); nullopt when malformed.
std::optional<Frame> parse_frame(std::string_view text);

}  // namespace wavebench::can
