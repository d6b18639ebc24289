#include "wavebench/canopen/cia402.hpp"

#include <fmt/format.h>

namespace wavebench::canopen {

Cia402State decode_state(std::uint16_t sw) noexcept {
  if ((sw & 0x4F) == 0x00) return Cia402State::not_ready_to_switch_on;
  if ((sw & 0x4F) == 0x40) return Cia402State::switch_on_disabled;
  if ((sw & 0x6F) == 0x21) return Cia402State::ready_to_switch_on;
  if ((sw & 0x6F) == 0x23) return Cia402State::switched_on;
  if ((sw & 0x6F) == 0x27) return Cia402State::operation_enabled;
  if ((sw & 0x6F) == 0x07) return Cia402State::quick_stop_active;
  if ((sw & 0x4F) == 0x0F) return Cia402State::fault_reaction_active;
  if ((sw & 0x4F) == 0x08) return Cia402State::fault;
  return Cia402State::unknown;
}

std::string_view to_string(Cia402State state) noexcept {
  switch (state) {
    case Cia402State::not_ready_to_switch_on:
      return "not ready to switch on";
    case Cia402State::switch_on_disabled:
      return "switch on disabled";
    case Cia402State::ready_to_switch_on:
      return "ready to switch on";
    case Cia402State::switched_on:
      return "switched on";
    case Cia402State::operation_enabled:
      return "operation enabled";
    case Cia402State::quick_stop_active:
      return "quick stop active";
    case Cia402State::fault_reaction_active:
      return "fault reaction active";
    case Cia402State::fault:
      return "fault";
    case Cia402State::unknown:
      return "unknown";
  }
  return "unknown";
}

std::string_view to_string(OperationMode mode) noexcept {
  switch (mode) {
    case OperationMode::profile_position:
      return "pp";
    case OperationMode::profile_velocity:
      return "pv";
    case OperationMode::profile_torque:
      return "pt";
    case OperationMode::homing:
      return "homing";
    case OperationMode::cyclic_sync_position:
      return "csp";
    case OperationMode::cyclic_sync_velocity:
      return "csv";
    case OperationMode::cyclic_sync_torque:
      return "cst";
  }
  return "unknown";
}

std::optional<OperationMode> parse_operation_mode(std::string_view text) noexcept {
  for (auto m :
       {OperationMode::profile_position, OperationMode::profile_velocity,
        OperationMode::profile_torque, OperationMode::homing, OperationMode::cyclic_sync_position,
        OperationMode::cyclic_sync_velocity, OperationMode::cyclic_sync_torque}) {
    if (text == to_string(m)) return m;
  }
  return std::nullopt;
}

std::optional<std::uint16_t> controlword_toward(Cia402State from, Cia402State target) noexcept {
  using S = Cia402State;
  namespace cw = controlword;
  if (from == target) return std::nullopt;
  switch (from) {
    case S::fault:
      return cw::fault_reset;  // 15
    case S::not_ready_to_switch_on:
    case S::fault_reaction_active:
    case S::unknown:
      return std::nullopt;
    case S::switch_on_disabled:
      return target == S::quick_stop_active ? std::nullopt : std::optional(cw::shutdown);  // 2
    case S::ready_to_switch_on:
      if (target == S::switch_on_disabled) return cw::disable_voltage;  // 7
      if (target == S::quick_stop_active) return std::nullopt;
      return cw::switch_on;  // 3
    case S::switched_on:
      if (target == S::switch_on_disabled) return cw::disable_voltage;  // 10
      if (target == S::ready_to_switch_on) return cw::shutdown;         // 6
      if (target == S::quick_stop_active) return std::nullopt;
      return cw::enable_operation;  // 4
    case S::operation_enabled:
      if (target == S::switch_on_disabled) return cw::disable_voltage;  // 9
      if (target == S::ready_to_switch_on) return cw::shutdown;         // 8
      if (target == S::switched_on) return cw::disable_operation;       // 5
      if (target == S::quick_stop_active) return cw::quick_stop;        // 11
      return std::nullopt;
    case S::quick_stop_active:
      if (target == S::operation_enabled) return cw::enable_operation;  // 16
      return cw::disable_voltage;                                       // 12
  }
  return std::nullopt;
}

std::string describe_statusword(std::uint16_t sw) {
  std::string text = fmt::format("{} (statusword 0x{:04X})", to_string(decode_state(sw)), sw);
  if ((sw & statusword::voltage_enabled) == 0) text += ", voltage off";
  if ((sw & statusword::warning) != 0) text += ", warning";
  if ((sw & statusword::remote) == 0) text += ", not remote";
  if ((sw & statusword::internal_limit) != 0) text += ", internal limit active";
  return text;
}

}  // namespace wavebench::canopen
