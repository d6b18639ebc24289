#include "wavebench/bench/quick_stop_watch.hpp"

#include "wavebench/canopen/cia402.hpp"

namespace wavebench::bench {

canopen::PdoConfig quick_stop_rpdo(canopen::NodeId drive) {
  canopen::PdoConfig c;
  c.cob_id = canopen::rpdo_cob_id(kQuickStopRpdo, drive);
  c.transmission_type = 255;  // event-driven: applied on reception, not at the next SYNC
  c.entries = {{0x6040, 0, 16}};
  return c;
}

can::Frame quick_stop_frame(canopen::NodeId drive) {
  can::Frame f;
  f.id = canopen::rpdo_cob_id(kQuickStopRpdo, drive);
  f.len = 2;
  f.data[0] = static_cast<std::uint8_t>(canopen::controlword::quick_stop & 0xFFU);
  f.data[1] = static_cast<std::uint8_t>(canopen::controlword::quick_stop >> 8);
  return f;
}

bool quick_stop_taken(std::uint16_t statusword) noexcept {
  using S = canopen::Cia402State;
  switch (canopen::decode_state(statusword)) {
    case S::not_ready_to_switch_on:
    case S::switch_on_disabled:
    case S::ready_to_switch_on:
    case S::quick_stop_active:
    case S::fault_reaction_active:
    case S::fault:
      return true;
    case S::switched_on:
    case S::operation_enabled:
    case S::unknown:
      return false;
  }
  return false;
}

void QuickStopWatch::start(double now_s, double timeout_s) noexcept {
  pending_ = true;
  deadline_s_ = now_s + timeout_s;
  last_.reset();
}

QuickStopWatch::Verdict QuickStopWatch::on_cycle(double now_s,
                                                 std::optional<std::uint16_t> statusword) noexcept {
  if (!pending_) return Verdict::kIdle;
  if (statusword) last_ = statusword;
  if (statusword && quick_stop_taken(*statusword)) {
    pending_ = false;
    return Verdict::kConfirmed;
  }
  if (now_s >= deadline_s_) {
    pending_ = false;
    return Verdict::kTimedOut;
  }
  return Verdict::kWaiting;
}

}  // namespace wavebench::bench
