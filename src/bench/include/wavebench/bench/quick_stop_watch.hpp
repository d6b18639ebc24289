#pragma once
// The servo drive's quick stop on a trip (bench.md §7), a path that never waits behind routine
// traffic: the controlword quick stop goes out in an event-driven RPDO of the drive, sent
// straight on the bus (never through the SDO client, whose one transfer at a time may be a
// long upload), and the drive's statusword, which arrives in TPDO1 every cycle, must then show
// the power stage off or quick stop active within a timeout; if it does not, the bench sends
// NMT stop to the drive node (a drive configured by 0x6007 = 2 disables its voltage on it).

#include <cstdint>
#include <optional>

#include "wavebench/can/frame.hpp"
#include "wavebench/canopen/cob_id.hpp"
#include "wavebench/canopen/pdo.hpp"

namespace wavebench::bench {

// RPDO1 of the drive, mapped at configuration to the controlword alone.
inline constexpr unsigned kQuickStopRpdo = 1;
// CiA 402 abort connection option code 0x6007 = 2: "disable voltage" when the drive enters NMT
// stopped (or loses its heartbeat, bus-off): what makes the NMT stop switch the power stage off.
inline constexpr std::int16_t kAbortConnectionDisableVoltage = 2;

canopen::PdoConfig quick_stop_rpdo(canopen::NodeId drive);
// The RPDO frame with controlword 0x0002 (quick stop, bits 0bxxxx x01x).
can::Frame quick_stop_frame(canopen::NodeId drive);
// Quick stop active, or a state with the power stage off (not ready to switch on, switch on
// disabled, ready to switch on, fault reaction active, fault).
bool quick_stop_taken(std::uint16_t statusword) noexcept;

// Bench time in, verdicts out; no bus, no clock of its own.
class QuickStopWatch {
 public:
  enum class Verdict { kIdle, kWaiting, kConfirmed, kTimedOut };

  void start(double now_s, double timeout_s) noexcept;
  // Once per cycle: the cycle's statusword, nullopt when the drive's TPDO1 did not arrive.
  Verdict on_cycle(double now_s, std::optional<std::uint16_t> statusword) noexcept;
  bool pending() const noexcept { return pending_; }
  // The last statusword seen while waiting (for the log), nullopt when none came.
  std::optional<std::uint16_t> last_statusword() const noexcept { return last_; }
  void reset() noexcept { *this = QuickStopWatch{}; }

 private:
  bool pending_ = false;
  double deadline_s_ = 0;
  std::optional<std::uint16_t> last_;
};

}  // namespace wavebench::bench
