#include "wavebench/simdevices/cia402_state_machine.hpp"

namespace wavebench::simdevices {
namespace {

// Controlword commands (CiA 402-2 table 25): the mask covers the bits the command defines.
bool is_shutdown(std::uint16_t cw) {
  return (cw & 0x0087) == 0x0006;
}
bool is_switch_on(std::uint16_t cw) {
  return (cw & 0x008F) == 0x0007;
}
bool is_enable_operation(std::uint16_t cw) {
  return (cw & 0x008F) == 0x000F;
}
bool is_disable_voltage(std::uint16_t cw) {
  return (cw & 0x0082) == 0x0000;
}
bool is_quick_stop(std::uint16_t cw) {
  return (cw & 0x0086) == 0x0002;
}

}  // namespace

std::string_view to_string(Cia402State state) noexcept {
  switch (state) {
    case Cia402State::kNotReadyToSwitchOn:
      return "not ready to switch on";
    case Cia402State::kSwitchOnDisabled:
      return "switch on disabled";
    case Cia402State::kReadyToSwitchOn:
      return "ready to switch on";
    case Cia402State::kSwitchedOn:
      return "switched on";
    case Cia402State::kOperationEnabled:
      return "operation enabled";
    case Cia402State::kQuickStopActive:
      return "quick stop active";
    case Cia402State::kFaultReactionActive:
      return "fault reaction active";
    case Cia402State::kFault:
      return "fault";
  }
  return "?";
}

void Cia402StateMachine::power_up() noexcept {
  if (state_ == Cia402State::kNotReadyToSwitchOn) state_ = Cia402State::kSwitchOnDisabled;
}

void Cia402StateMachine::apply_controlword(std::uint16_t cw) noexcept {
  const bool reset_edge = (cw & 0x0080) && !(last_controlword_ & 0x0080);
  last_controlword_ = cw;
  switch (state_) {
    case Cia402State::kNotReadyToSwitchOn:
    case Cia402State::kFaultReactionActive:
      break;
    case Cia402State::kFault:
      if (reset_edge) state_ = Cia402State::kSwitchOnDisabled;  // 15
      break;
    case Cia402State::kSwitchOnDisabled:
      if (is_shutdown(cw)) state_ = Cia402State::kReadyToSwitchOn;  // 2
      break;
    case Cia402State::kReadyToSwitchOn:
      if (is_disable_voltage(cw) || is_quick_stop(cw)) {
        state_ = Cia402State::kSwitchOnDisabled;  // 7
      } else if (is_switch_on(cw)) {
        state_ = Cia402State::kSwitchedOn;  // 3
      } else if (is_enable_operation(cw)) {
        // Many drives (and masters) go straight through Switched on: 3 then 4.
        state_ = Cia402State::kOperationEnabled;
      }
      break;
    case Cia402State::kSwitchedOn:
      if (is_disable_voltage(cw) || is_quick_stop(cw)) {
        state_ = Cia402State::kSwitchOnDisabled;  // 10
      } else if (is_shutdown(cw)) {
        state_ = Cia402State::kReadyToSwitchOn;  // 6
      } else if (is_enable_operation(cw)) {
        state_ = Cia402State::kOperationEnabled;  // 4
      }
      break;
    case Cia402State::kOperationEnabled:
      if (is_disable_voltage(cw)) {
        state_ = Cia402State::kSwitchOnDisabled;  // 9
      } else if (is_quick_stop(cw)) {
        state_ = Cia402State::kQuickStopActive;  // 11
      } else if (is_shutdown(cw)) {
        state_ = Cia402State::kReadyToSwitchOn;  // 8
      } else if (is_switch_on(cw)) {
        state_ = Cia402State::kSwitchedOn;  // 5
      }
      break;
    case Cia402State::kQuickStopActive:
      if (is_disable_voltage(cw)) {
        state_ = Cia402State::kSwitchOnDisabled;  // 12
      } else if (is_enable_operation(cw)) {
        state_ = Cia402State::kOperationEnabled;  // 16
      }
      break;
  }
}

void Cia402StateMachine::fault() noexcept {
  if (state_ != Cia402State::kFault) state_ = Cia402State::kFaultReactionActive;
}

void Cia402StateMachine::fault_reaction_done() noexcept {
  if (state_ == Cia402State::kFaultReactionActive) state_ = Cia402State::kFault;
}

void Cia402StateMachine::quick_stop_done(bool to_switch_on_disabled) noexcept {
  if (state_ == Cia402State::kQuickStopActive && to_switch_on_disabled) {
    state_ = Cia402State::kSwitchOnDisabled;
  }
}

std::uint16_t Cia402StateMachine::state_bits() const noexcept {
  switch (state_) {
    case Cia402State::kNotReadyToSwitchOn:
      return 0x0000;
    case Cia402State::kSwitchOnDisabled:
      return 0x0040;
    case Cia402State::kReadyToSwitchOn:
      return 0x0031;
    case Cia402State::kSwitchedOn:
      return 0x0033;
    case Cia402State::kOperationEnabled:
      return 0x0037;
    case Cia402State::kQuickStopActive:
      return 0x0017;
    case Cia402State::kFaultReactionActive:
      return 0x001F;
    case Cia402State::kFault:
      return 0x0008;
  }
  return 0;
}

bool Cia402StateMachine::power_stage_on() const noexcept {
  return state_ == Cia402State::kOperationEnabled || state_ == Cia402State::kQuickStopActive ||
         state_ == Cia402State::kFaultReactionActive;
}

}  // namespace wavebench::simdevices
