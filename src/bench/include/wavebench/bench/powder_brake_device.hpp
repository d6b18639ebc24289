#pragma once
// The magnetic-powder brake's controller (bench.md §3, Modbus) as a bench device. State
// interfaces: brake_current [A] and brake_torque [N*m], from the supervisor's latest readback
// while it is fresh (the controller is not on the SYNC: its values join each cycle at its end).
// Command interface: brake_torque_setpoint [N*m]. One Modbus link (one libmodbus context) for
// the bench's commands and the supervisor's heartbeats and polls; the safe-state write goes
// ahead of queued polls.
//
// Beats in bench time: on the simulated clock the controller's watchdog counts bench time (the
// in-process plant steps the brake by SYNC), so the bench writes the heartbeat register every
// heartbeat period of bench time (beat_if_due) beside the supervisor's real-time link watch.

#include <atomic>
#include <memory>
#include <optional>
#include <string>

#include "wavebench/bench/bench_device.hpp"
#include "wavebench/modbus/brake_client.hpp"
#include "wavebench/modbus/brake_supervisor.hpp"

namespace wavebench::bench {

class PowderBrakeDevice final : public BenchDevice {
 public:
  PowderBrakeDevice(modbus::BrakeClientConfig config, modbus::BrakeEventSink& events);
  ~PowderBrakeDevice() override;

  std::vector<storage::ChannelInfo> channels() const override;
  std::vector<CommandInterface> commands() const override;
  std::string describe() const override;

  // Connects, resets a latched alarm, output off, torque mode, and starts the supervisor.
  // `beats_in_bench_time`: see above. Throws naming the controller's address.
  void connect(bool beats_in_bench_time);
  // Output off, supervisor stopped, watchdog switched off (a real controller latches a watchdog
  // alarm when the heartbeats stop with it armed), link closed. Never throws.
  void disconnect() noexcept;
  bool connected() const noexcept { return client_ != nullptr; }

  // Output off then setpoint 0; false when the controller did not confirm (retried by
  // retry_safe_state() when the link returns; its watchdog switches the output off meanwhile).
  bool make_safe() noexcept;
  bool safe_state_pending() const noexcept { return safe_pending_; }
  void retry_safe_state() noexcept;
  // Torque setpoint with a ramp [N*m/s, 0 = step], then the output on where `output_on` (an
  // inactive bench keeps it off). Throws on a link error.
  void set_torque(double torque_nm, double ramp_nm_per_s, bool output_on);
  // After a trip: alarm reset, output off, torque mode. Throws on a link error.
  void reset_after_fault();
  void beat_if_due(double bench_now_s) noexcept;

  // The supervisor's latest readback while it is fresh (three heartbeat periods).
  std::optional<modbus::BrakeReadback> fresh_readback() const;
  // The readback the last cycle carried (on_cycle_end), for the cycle's checks.
  const std::optional<modbus::BrakeReadback>& cycle_readback() const noexcept { return cycle_; }
  bool link_lost() const noexcept;
  std::string last_error() const;
  modbus::BrakeClient* client() noexcept { return client_.get(); }

  void on_cycle_end(CycleRecord& record) noexcept override;
  void on_state_change(BenchLifecycle state) noexcept override;

  // The idle watch: the controller's output on while the bench is not active means someone
  // else energised it (another Modbus master, a front panel). The reason, once per readback
  // taken after the bench went idle (plus a response time and a poll, so a readback that
  // straddled the bench's own switch-off does not count); nothing otherwise.
  std::optional<std::string> energised_while_idle();

 private:
  modbus::BrakeClientConfig config_;
  modbus::BrakeEventSink& events_;
  std::unique_ptr<modbus::BrakeClient> client_;
  std::unique_ptr<modbus::BrakeSupervisor> supervisor_;
  bool beats_in_bench_time_ = false;
  double next_beat_s_ = 0;
  bool safe_pending_ = false;
  std::optional<modbus::BrakeReadback> cycle_;
  std::atomic<BenchLifecycle> state_{BenchLifecycle::kUnconfigured};
  std::atomic<modbus::BrakeClient::Clock::rep> idle_since_{0};
  modbus::BrakeClient::Clock::time_point last_reported_{};
};

}  // namespace wavebench::bench
