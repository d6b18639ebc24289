#pragma once
// The simulated bench on a CAN bus: servo drive, output encoder and torque sensor backed by one
// SimulatedBenchPlant, plus an optional brake coupling (the simulated Modbus brake controller).
//
// Clocks: kManual (the owner calls advance()), kSyncDriven (every SYNC received advances the
// simulation by one communication cycle period, 0x1006 or the config's period: faster than
// real time, deterministic), kRealTime (a timer on the bus's io_context follows the steady
// clock). Everything runs on the bus's io_context thread; nothing here locks.

#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>

#include "wavebench/can/can_bus.hpp"
#include "wavebench/model/gear_params.hpp"
#include "wavebench/simdevices/bench_plant.hpp"
#include "wavebench/simdevices/output_encoder.hpp"
#include "wavebench/simdevices/servo_drive.hpp"
#include "wavebench/simdevices/torque_sensor.hpp"

namespace wavebench::simdevices {

enum class BenchClock { kManual, kSyncDriven, kRealTime };

struct SimulatedBenchConfig {
  // The unit's true gear, a twin case's (the bench factory's true_gear, simbench --gear, or
  // configs/benches/simulated-devices-gear.yaml); none (ratio 0): the plant refuses it.
  model::GearParams gear;
  ServoDriveConfig drive;
  EncoderConfig encoder;
  TorqueSensorConfig torque_sensor;
  // A CiA 406 encoder on the input (motor) shaft as its own node; absent by default.
  std::optional<EncoderConfig> input_encoder;
  BenchClock clock = BenchClock::kSyncDriven;
  double sync_period = 1e-3;  // [s] sync-driven step while the drive's 0x1006 is 0
  double tick = 1e-3;         // [s] real-time timer period
  double brake_torque = 0;    // [N*m] brake setting when no coupling is installed
};

// Called once per tick with the output speed [rad/s, model direction] and the tick [s];
// returns the brake's available torque [N*m]. Must not throw.
using BrakeCoupling = std::function<double(double omega_out, double dt)>;

class SimulatedBench {
 public:
  SimulatedBench(const SimulatedBenchConfig& config, can::CanBus& bus);
  ~SimulatedBench();
  SimulatedBench(const SimulatedBench&) = delete;
  SimulatedBench& operator=(const SimulatedBench&) = delete;

  // Boots the nodes (boot-up messages) and, on the real-time clock, starts the timer.
  void start();
  void stop();
  // Advances simulated time by dt [s]: servo loop, mechanics, sensors, node timers.
  void advance(double dt);
  double now() const noexcept { return now_; }

  void set_brake_coupling(BrakeCoupling coupling) { brake_coupling_ = std::move(coupling); }
  void set_brake_torque(double torque_nm) { plant_.set_brake_torque(torque_nm); }

  Cia402ServoDrive& drive() noexcept { return drive_; }
  Cia406Encoder& encoder() noexcept { return encoder_; }
  Cia406Encoder* input_encoder() noexcept { return input_encoder_ ? &*input_encoder_ : nullptr; }
  TorqueSensor& torque_sensor() noexcept { return torque_sensor_; }
  SimulatedBenchPlant& plant() noexcept { return plant_; }
  const SimulatedBenchConfig& config() const noexcept { return config_; }
  // Every node silent (true) or speaking again (false): a cut bus as the master sees it.
  void set_silent(bool silent) noexcept;
  std::uint64_t frames_sent() const noexcept { return frames_sent_; }
  std::uint64_t send_errors() const noexcept { return send_errors_; }
  // Real-time clock only: simulated time the bench gave up because it could not keep up [s].
  double real_time_slip() const noexcept { return real_time_slip_; }

 private:
  void handle(const can::Frame& frame) noexcept;
  void advance_chunk(double dt);
  void observe_sensors();
  void schedule_tick();
  void follow_real_time();
  FrameSink sink();

  SimulatedBenchConfig config_;
  can::CanBus& bus_;
  SimulatedBenchPlant plant_;
  Cia402ServoDrive drive_;
  Cia406Encoder encoder_;
  TorqueSensor torque_sensor_;
  std::optional<Cia406Encoder> input_encoder_;
  BrakeCoupling brake_coupling_;
  double now_ = 0;
  int direction_sign_ = 1;
  std::uint64_t frames_sent_ = 0;
  std::uint64_t send_errors_ = 0;
  bool running_ = false;
  std::chrono::steady_clock::time_point t0_{};
  double real_time_slip_ = 0;
  boost::asio::steady_timer timer_;
  can::CanBus::Subscription subscription_;
};

}  // namespace wavebench::simdevices
