#pragma once
// The CiA 402 power drive state machine (CiA 402-2 §7.1): controlword commands, the fault
// path and the statusword's state bits. It knows nothing of motion; Cia402ServoDrive asks it
// whether the power stage is enabled and tells it when a quick stop or fault reaction ended.

#include <cstdint>
#include <string_view>

namespace wavebench::simdevices {

enum class Cia402State {
  kNotReadyToSwitchOn,
  kSwitchOnDisabled,
  kReadyToSwitchOn,
  kSwitchedOn,
  kOperationEnabled,
  kQuickStopActive,
  kFaultReactionActive,
  kFault,
};

std::string_view to_string(Cia402State state) noexcept;

class Cia402StateMachine {
 public:
  Cia402State state() const noexcept { return state_; }

  // Self-test done: Not ready to switch on -> Switch on disabled (transition 1).
  void power_up() noexcept;
  // A new controlword; fault reset acts on the rising edge of bit 7 only.
  void apply_controlword(std::uint16_t controlword) noexcept;
  // A fault: any state -> Fault reaction active (13).
  void fault() noexcept;
  // The drive finished its fault reaction (14) or its quick stop ramp (12 when the quick stop
  // option code says to leave Quick stop active).
  void fault_reaction_done() noexcept;
  void quick_stop_done(bool to_switch_on_disabled) noexcept;
  void reset() noexcept { *this = Cia402StateMachine{}; }

  // The state bits 0-3, 5, 6 of the statusword, plus bit 4 (voltage enabled).
  std::uint16_t state_bits() const noexcept;
  // Torque is applied in Operation enabled, Quick stop active and Fault reaction active.
  bool power_stage_on() const noexcept;

 private:
  Cia402State state_ = Cia402State::kNotReadyToSwitchOn;
  std::uint16_t last_controlword_ = 0;
};

}  // namespace wavebench::simdevices
