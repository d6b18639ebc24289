#pragma once
// SDO abort codes (CiA 301 §7.2.4.3.17) the simulated servers send.

#include <cstdint>

namespace wavebench::simdevices::sdo_abort {

inline constexpr std::uint32_t kNone = 0;
inline constexpr std::uint32_t kToggleBit = 0x05030000;
inline constexpr std::uint32_t kTimeout = 0x05040000;
inline constexpr std::uint32_t kBadCommand = 0x05040001;
inline constexpr std::uint32_t kUnsupportedAccess = 0x06010000;
inline constexpr std::uint32_t kWriteOnly = 0x06010001;
inline constexpr std::uint32_t kReadOnly = 0x06010002;
inline constexpr std::uint32_t kNoObject = 0x06020000;
inline constexpr std::uint32_t kNotMappable = 0x06040041;
inline constexpr std::uint32_t kPdoTooLong = 0x06040042;
inline constexpr std::uint32_t kLengthMismatch = 0x06070010;
inline constexpr std::uint32_t kNoSubIndex = 0x06090011;
inline constexpr std::uint32_t kValueRange = 0x06090030;
inline constexpr std::uint32_t kGeneral = 0x08000000;
inline constexpr std::uint32_t kDeviceState = 0x08000022;

}  // namespace wavebench::simdevices::sdo_abort
