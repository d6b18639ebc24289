#pragma once
// The Bench over CANopen and Modbus (bench.md §1, §7), assembled from parts with one job each:
//
//   devices        one driver object per bench device (bench_device.hpp): the CiA 402 servo
//                  drive, the output encoder and the torque sensor (and the config's further
//                  `devices:`), each configuring its node and writing its named channels into
//                  the cycle's record; the powder brake's controller over Modbus
//   cycle engine   SYNC from the injected clock (real or simulated, cycle_clock.hpp), the
//                  devices' TPDOs into one sample per cycle, observers (cycle_engine.hpp)
//   this class     the lifecycle (bench_lifecycle.hpp), the blocking calls procedures make, and
//                  safety: heartbeats (heartbeat_watch.hpp) or node guarding of a device without
//                  a heartbeat producer (node_guard_watch.hpp), both on the wall clock, EMCY,
//                  limits, the brake's link, and the trip path that never waits
//                  (quick_stop_watch.hpp)
//
// The brake controller's watchdog and physics count bench time on the simulated clock, so the
// brake device beats in bench time there (powder_brake_device.hpp).

#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/bench/bench.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/cia402_drive_device.hpp"
#include "wavebench/bench/cycle_clock.hpp"
#include "wavebench/bench/cycle_engine.hpp"
#include "wavebench/bench/heartbeat_watch.hpp"
#include "wavebench/bench/node_guard_watch.hpp"
#include "wavebench/bench/powder_brake_device.hpp"
#include "wavebench/bench/quick_stop_watch.hpp"
#include "wavebench/bench/safety_limits_check.hpp"
#include "wavebench/can/can_bus.hpp"
#include "wavebench/canopen/master.hpp"
#include "wavebench/modbus/brake_supervisor.hpp"

namespace wavebench::bench {

class CanopenBench final : public Bench, private modbus::BrakeEventSink {
 public:
  // `bus` (and its io_context) must outlive the bench; the bench thread runs that io_context.
  CanopenBench(BenchConfig config, can::CanBus& bus);
  ~CanopenBench() override;

  const BenchDescription& description() const noexcept override { return config_.description; }
  std::vector<storage::ChannelInfo> extra_channels() const override;
  std::vector<BenchDeviceInfo> device_info() const override;
  void connect() override;
  void disconnect() noexcept override;
  BenchLifecycle state() const noexcept override { return lifecycle_.load(); }
  std::string fault_reason() const override;
  void clear_fault() override;
  void activate() override;
  void deactivate() noexcept override;

  void move_input_to(double theta_in_rad, double speed_rad_s) override;
  void run_input_velocity(double omega_in_rad_s) override;
  void stop_motion() override;
  void set_brake_torque(double torque_nm, double ramp_nm_per_s = 0) override;
  void wait_for(double seconds) override;
  bool wait_until(const std::function<bool()>& done, double timeout_s) override;
  void idle_for(double seconds) override;
  double now() const override { return clock_->now(); }
  const storage::SyncSample& latest_sample() const override { return engine_->latest().sample; }

  void add_observer(SampleObserver& observer) override { engine_->add_observer(observer); }
  void remove_observer(SampleObserver& observer) override { engine_->remove_observer(observer); }
  AcquisitionStats acquisition_stats() const override;
  void request_stop(const std::string& reason) noexcept override;

  const BenchConfig& config() const noexcept { return config_; }
  canopen::Master& master() noexcept { return *master_; }
  // The bench's devices: the drive, the output encoder, the torque sensor, the config's further
  // devices (CANopen), then the brake controller.
  std::vector<const BenchDevice*> devices() const;
  // Real clock: every SYNC tick (deadline and send time), e.g. for a jitter benchmark.
  void on_sync_tick(std::function<void(const canopen::SyncProducer::Tick&)> hook) {
    tick_hook_ = std::move(hook);
  }
  // The brake supervisor's latest readback while it is fresh (the commissioning check).
  std::optional<modbus::BrakeReadback> brake_readback() const { return brake_->fresh_readback(); }
  // Drive values of the last cycle (statusword, following error).
  const DriveCycleValues& latest_drive() const noexcept { return engine_->latest().drive; }
  // The drive's units and optional objects as found at the last connect.
  const DriveChannels& drive_channels() const noexcept { return drive_->drive_channels(); }
  std::vector<std::string> absent_channels() const override {
    return drive_->drive_channels().absent_names();
  }
  // The nodes supervised by node guarding instead of heartbeats (no producer, or the config's
  // can.node_guarding.nodes), as found at the last connect.
  const NodeGuardWatch& node_guards() const noexcept { return guards_; }
  // The devices a SYNC waited for (simulated clock: slower than the configured rate).
  const std::vector<std::string>& late_devices() const noexcept { return engine_->late_devices(); }

 private:
  void on_brake_event(const modbus::BrakeEvent& event) noexcept override;

  void set_state(BenchLifecycle state) noexcept;
  void configure_nodes();
  void start_acquisition();
  void stop_acquisition() noexcept;
  void check_cycle(const CycleRecord& record) noexcept;
  void on_heartbeat_frame(const can::Frame& frame) noexcept;
  // Heartbeats and node guarding, judged on the wall clock: every cycle and on a timer.
  void watch_liveness() noexcept;
  void check_liveness() noexcept;
  void guard_node(CanopenDevice& device, canopen::SdoClient& sdo, const std::string& why);
  std::vector<CanopenDevice*> canopen_devices() const;
  std::vector<canopen::NodeId> all_nodes() const;
  std::string node_name(canopen::NodeId node) const;

  void trip(const std::string& reason) noexcept;
  void quick_stop_drive() noexcept;
  // Each cycle after a quick stop: confirmed by the statusword, or NMT stop when it is late.
  void watch_quick_stop(const DriveCycleValues& drive) noexcept;
  void stop_drive_by_nmt() noexcept;
  void finish_safe_state() noexcept;
  // Drive power stage off: to `target`, from wherever the drive is; a drive in fault stays
  // there (its power stage is off; clearing it is the operator's reset).
  void power_down_drive(canopen::Cia402State target) noexcept;
  void nodes_to_preoperational() noexcept;

  // Runs the event loop until done() or `timeout_s` of bench time; throws BenchAborted when
  // the bench trips (unless `tolerate_fault`).
  bool run_until(const std::function<bool()>& done, double timeout_s, bool tolerate_fault = false);
  void run_once();
  void ensure_operational();
  void throw_if_tripped();
  void set_mode(canopen::OperationMode mode);
  template <typename F>
  void drive_command(const char* what, F&& f);
  template <typename F>
  void brake_command(const char* what, F&& f);

  BenchConfig config_;
  can::CanBus& bus_;
  boost::asio::io_context& io_;
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
  boost::asio::steady_timer liveness_timer_{io_};
  std::chrono::steady_clock::time_point last_liveness_check_{};

  std::unique_ptr<canopen::Master> master_;
  std::unique_ptr<CycleClock> clock_;
  std::unique_ptr<CycleEngine> engine_;
  std::unique_ptr<Cia402DriveDevice> drive_;
  // The output encoder, the torque sensor, then config.devices in order.
  std::vector<std::unique_ptr<CanopenDevice>> sensors_;
  std::unique_ptr<PowderBrakeDevice> brake_;
  SafetyLimitsCheck limits_check_;
  HeartbeatWatch heartbeats_;
  NodeGuardWatch guards_;
  std::vector<can::CanBus::Subscription> subscriptions_;
  double bus_load_ = 0;

  std::atomic<BenchLifecycle> lifecycle_{BenchLifecycle::kUnconfigured};
  mutable std::mutex reason_mutex_;
  std::string reason_;
  bool tripped_ = false;
  QuickStopWatch quick_stop_watch_;
  bool powered_ = false;  // the drive was enabled and not yet powered down
  bool acquiring_ = false;
  std::function<void(const canopen::SyncProducer::Tick&)> tick_hook_;
  std::optional<canopen::OperationMode> mode_;
};

}  // namespace wavebench::bench
