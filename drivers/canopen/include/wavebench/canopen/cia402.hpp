#pragma once
// CiA 402 vocabulary: states decoded from the statusword, the controlword commands of every
// state-machine transition, and the modes of operation. Pure functions, no bus.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace wavebench::canopen {

enum class Cia402State {
  not_ready_to_switch_on,
  switch_on_disabled,
  ready_to_switch_on,
  switched_on,
  operation_enabled,
  quick_stop_active,
  fault_reaction_active,
  fault,
  unknown,
};

enum class OperationMode : std::int8_t {
  profile_position = 1,
  profile_velocity = 3,
  profile_torque = 4,
  homing = 6,
  cyclic_sync_position = 8,
  cyclic_sync_velocity = 9,
  cyclic_sync_torque = 10,
};

namespace controlword {
inline constexpr std::uint16_t shutdown = 0x0006;
inline constexpr std::uint16_t switch_on = 0x0007;
inline constexpr std::uint16_t disable_operation = 0x0007;
inline constexpr std::uint16_t enable_operation = 0x000F;
inline constexpr std::uint16_t disable_voltage = 0x0000;
inline constexpr std::uint16_t quick_stop = 0x0002;
inline constexpr std::uint16_t fault_reset = 0x0080;         // acts on the rising edge only
inline constexpr std::uint16_t new_set_point = 0x0010;       // PP bit 4
inline constexpr std::uint16_t change_immediately = 0x0020;  // PP bit 5
inline constexpr std::uint16_t relative = 0x0040;            // PP bit 6
inline constexpr std::uint16_t halt = 0x0100;
inline constexpr std::uint16_t command_mask = 0x008F;  // bits 0-3 and 7 select the transition
}  // namespace controlword

namespace statusword {
inline constexpr std::uint16_t voltage_enabled = 0x0010;
inline constexpr std::uint16_t quick_stop = 0x0020;  // 0 = quick stop active
inline constexpr std::uint16_t warning = 0x0080;
inline constexpr std::uint16_t remote = 0x0200;
inline constexpr std::uint16_t target_reached = 0x0400;
inline constexpr std::uint16_t internal_limit = 0x0800;
inline constexpr std::uint16_t bit12 = 0x1000;  // PP set-point acknowledge, PV speed zero,
                                                // CSP/CSV target value ignored... (mode specific)
inline constexpr std::uint16_t bit13 = 0x2000;  // PP/CSP following error, PV max slippage
}  // namespace statusword

Cia402State decode_state(std::uint16_t statusword) noexcept;
std::string_view to_string(Cia402State state) noexcept;
std::string_view to_string(OperationMode mode) noexcept;
std::optional<OperationMode> parse_operation_mode(std::string_view text) noexcept;

// The controlword that takes the drive one transition from `from` toward `target` (CiA 402
// transitions 2-12, 15, 16); nullopt when there is nothing to command (already there, or a
// state the drive leaves on its own: not ready, fault reaction). From fault the answer is the
// fault-reset bit: the caller must send it as a rising edge (bit 7 low first).
std::optional<std::uint16_t> controlword_toward(Cia402State from, Cia402State target) noexcept;

// A human sentence for a statusword, e.g. "switch on disabled (0x0250), voltage off".
std::string describe_statusword(std::uint16_t statusword);

}  // namespace wavebench::canopen
