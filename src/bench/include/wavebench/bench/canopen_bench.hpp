#pragma once
// The Bench over CANopen and Modbus (bench.md §1, §7): a canopen::Master on a CAN bus drives the
// CiA 402 servo, reads the CiA 406 output encoder and the torque sensor by synchronous TPDOs,
// and the powder brake is commanded over Modbus from the bench thread (modbus::BrakeClient)
// while a modbus::BrakeSupervisor thread feeds its watchdog and reads it back over the same
// link (one libmodbus context; the safe-state write goes before the supervisor's polls).
//
// Real clock: canopen::SyncProducer on absolute deadlines; a cycle closes when all its PDOs
// arrived or at the next SYNC. Simulated clock: the next SYNC goes out as soon as the cycle's
// PDOs arrived (or after can.cycle_timeout of real time, the missing ones counted), and bench
// time is SYNC index × period.
//
// Brake and the simulated clock: the controller's watchdog and its physics count bench time
// (the in-process plant steps the brake by SYNC), while the supervisor's heartbeat is real
// time. So on the simulated clock the bench thread also writes the heartbeat register every
// heartbeat period of bench time: the watchdog keeps its meaning in bench time, and the
// supervisor's real-time link-loss detection is unchanged. Heartbeats of the CANopen nodes are
// likewise watched in bench time on the simulated clock (the simulated nodes produce them in
// bench time) and by canopen::HeartbeatConsumer (real time) on the real clock.

#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/bench/bench.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/channel_device.hpp"
#include "wavebench/bench/quick_stop_watch.hpp"
#include "wavebench/bench/drive_channels.hpp"
#include "wavebench/bench/safety_limits_check.hpp"
#include "wavebench/bench/sample_assembler.hpp"
#include "wavebench/bench/sync_lateness_histogram.hpp"
#include "wavebench/can/can_bus.hpp"
#include "wavebench/canopen/cia402_drive.hpp"
#include "wavebench/canopen/cia406_encoder.hpp"
#include "wavebench/canopen/master.hpp"
#include "wavebench/canopen/torque_sensor.hpp"
#include "wavebench/modbus/brake_client.hpp"
#include "wavebench/modbus/brake_supervisor.hpp"

namespace wavebench::bench {

class CanopenBench final : public Bench, private modbus::BrakeEventSink {
 public:
  // `bus` (and its io_context) must outlive the bench; the bench thread runs that io_context.
  CanopenBench(BenchConfig config, can::CanBus& bus);
  ~CanopenBench() override;

  const BenchDescription& description() const noexcept override { return config_.description; }
  std::vector<storage::ChannelInfo> extra_channels() const override;
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
  double now() const override;
  const storage::SyncSample& latest_sample() const override { return latest_; }

  void add_observer(SampleObserver& observer) override;
  void remove_observer(SampleObserver& observer) override;
  AcquisitionStats acquisition_stats() const override;
  void request_stop(const std::string& reason) noexcept override;

  const BenchConfig& config() const noexcept { return config_; }
  canopen::Master& master() noexcept { return *master_; }
  // Real clock: every SYNC tick (deadline and send time), e.g. for a jitter benchmark.
  void on_sync_tick(std::function<void(const canopen::SyncProducer::Tick&)> hook) {
    tick_hook_ = std::move(hook);
  }
  // The brake supervisor's latest readback while it is fresh (the commissioning check).
  std::optional<modbus::BrakeReadback> brake_readback() const { return fresh_brake_readback(); }
  // Drive values of the last cycle (statusword, following error).
  const DriveCycleValues& latest_drive() const noexcept { return latest_drive_; }
  // The drive's units and optional objects as found at the last connect.
  const DriveChannels& drive_channels() const noexcept { return drive_channels_; }
  std::vector<std::string> absent_channels() const override {
    return drive_channels_.absent_names();
  }

 private:
  void on_brake_event(const modbus::BrakeEvent& event) noexcept override;

  void connect_brake();
  void configure_nodes();
  void start_acquisition();
  void stop_acquisition() noexcept;
  void begin_cycle(std::uint64_t index, std::int64_t time_ns);
  void on_pdo(unsigned which, const can::Frame& frame) noexcept;
  void on_extra_pdo(std::size_t device, const can::Frame& frame) noexcept;
  void configure_channel_devices();
  std::vector<canopen::NodeId> all_nodes() const;
  void finish_cycle() noexcept;
  void send_simulated_sync() noexcept;
  void watch_heartbeats_in_bench_time() noexcept;
  void on_heartbeat_frame(const can::Frame& frame) noexcept;

  void trip(const std::string& reason) noexcept;
  void make_brake_safe() noexcept;
  void quick_stop_drive() noexcept;
  // Each cycle after a quick stop: confirmed by the statusword, or NMT stop when it is late.
  void watch_quick_stop() noexcept;
  void stop_drive_by_nmt() noexcept;
  void finish_safe_state() noexcept;
  // Drive power stage off: to `target`, from wherever the drive is; a drive in fault stays
  // there (its power stage is off; clearing it is the operator's reset).
  void power_down_drive(canopen::Cia402State target) noexcept;
  void release_brake_watchdog() noexcept;
  void nodes_to_preoperational() noexcept;

  // Runs the event loop until done() or `timeout_s` of bench time; throws BenchAborted when
  // the bench trips (unless `tolerate_fault`).
  bool run_until(const std::function<bool()>& done, double timeout_s, bool tolerate_fault = false);
  void run_once();
  void ensure_ready();
  void throw_if_tripped();
  void set_mode(canopen::OperationMode mode);
  template <typename F>
  void drive_command(const char* what, F&& f);
  template <typename F>
  void brake_command(const char* what, F&& f);
  std::optional<modbus::BrakeReadback> fresh_brake_readback() const;
  std::string node_name(canopen::NodeId node) const;
  std::chrono::steady_clock::time_point real_now() const {
    return std::chrono::steady_clock::now();
  }

  BenchConfig config_;
  can::CanBus& bus_;
  boost::asio::io_context& io_;
  DriveChannels drive_channels_;
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);

  std::unique_ptr<canopen::Master> master_;
  std::unique_ptr<canopen::Cia402Drive> drive_;
  std::unique_ptr<canopen::Cia406Encoder> encoder_;
  std::unique_ptr<canopen::TorqueSensor> torque_;
  std::unique_ptr<SampleAssembler> assembler_;
  std::vector<std::unique_ptr<ChannelDevice>> channel_devices_;  // config.devices, in order
  SafetyLimitsCheck limits_check_;
  std::vector<can::CanBus::Subscription> subscriptions_;

  std::unique_ptr<modbus::BrakeClient> brake_;
  std::unique_ptr<modbus::BrakeSupervisor> brake_supervisor_;
  bool brake_safe_pending_ = false;
  double next_brake_heartbeat_ = 0;

  std::atomic<BenchLifecycle> lifecycle_{BenchLifecycle::kUnconfigured};
  mutable std::mutex reason_mutex_;
  std::string reason_;
  bool tripped_ = false;
  QuickStopWatch quick_stop_watch_;
  bool powered_ = false;  // the drive was enabled and not yet powered down

  std::vector<SampleObserver*> observers_;
  storage::SyncSample latest_;
  DriveCycleValues latest_drive_;
  std::uint64_t samples_ = 0;
  AcquisitionStats stats_;
  SyncLatenessHistogram lateness_;
  std::function<void(const canopen::SyncProducer::Tick&)> tick_hook_;

  bool acquiring_ = false;
  std::chrono::steady_clock::time_point t0_{};
  std::uint64_t sync_index_ = 0;                            // the open (or last) cycle's SYNC index
  std::chrono::system_clock::time_point sync_sent_wall_{};  // real clock: the open cycle's SYNC
  boost::asio::steady_timer cycle_timer_;
  std::uint64_t cycle_generation_ = 0;
  std::map<canopen::NodeId, double> last_heartbeat_;  // bench time, simulated clock
  std::map<canopen::NodeId, std::uint8_t> node_state_;
  std::chrono::steady_clock::time_point last_drive_heartbeat_{};  // processed, real time
  std::optional<canopen::OperationMode> mode_;
};

}  // namespace wavebench::bench
