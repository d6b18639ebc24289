#include "wavebench/bench/bench_factory.hpp"

#include <boost/asio/io_context.hpp>
#include <cmath>

#include "wavebench/bench/canopen_bench.hpp"
#include "wavebench/can/socket_can_bus.hpp"
#include "wavebench/can/virtual_can_bus.hpp"
#include "wavebench/config/config_error.hpp"
#include "wavebench/config/twin_case.hpp"
#include "wavebench/model/stiffness_scaling.hpp"
#include "wavebench/simdevices/brake_server.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"

namespace wavebench::bench {
namespace {

// Forwards the Bench interface to a CanopenBench; subclasses own what it runs on. The
// CanopenBench member is reset first in every subclass destructor, before its bus goes.
class ForwardingBench : public Bench {
 public:
  const BenchDescription& description() const noexcept override { return inner_->description(); }
  std::vector<storage::ChannelInfo> extra_channels() const override {
    return inner_->extra_channels();
  }
  std::vector<BenchDeviceInfo> device_info() const override { return inner_->device_info(); }
  void connect() override { inner_->connect(); }
  void disconnect() noexcept override { inner_->disconnect(); }
  BenchLifecycle state() const noexcept override { return inner_->state(); }
  std::string fault_reason() const override { return inner_->fault_reason(); }
  void clear_fault() override { inner_->clear_fault(); }
  void activate() override { inner_->activate(); }
  void deactivate() noexcept override { inner_->deactivate(); }
  void move_input_to(double theta, double speed) override { inner_->move_input_to(theta, speed); }
  void run_input_velocity(double omega) override { inner_->run_input_velocity(omega); }
  void stop_motion() override { inner_->stop_motion(); }
  void set_brake_torque(double t, double ramp) override { inner_->set_brake_torque(t, ramp); }
  void wait_for(double seconds) override { inner_->wait_for(seconds); }
  bool wait_until(const std::function<bool()>& done, double timeout_s) override {
    return inner_->wait_until(done, timeout_s);
  }
  void idle_for(double seconds) override { inner_->idle_for(seconds); }
  double now() const override { return inner_->now(); }
  const storage::SyncSample& latest_sample() const override { return inner_->latest_sample(); }
  void add_observer(SampleObserver& o) override { inner_->add_observer(o); }
  void remove_observer(SampleObserver& o) override { inner_->remove_observer(o); }
  AcquisitionStats acquisition_stats() const override { return inner_->acquisition_stats(); }
  std::vector<std::string> absent_channels() const override { return inner_->absent_channels(); }
  void request_stop(const std::string& reason) noexcept override { inner_->request_stop(reason); }

  CanopenBench& canopen_bench() { return *inner_; }

 protected:
  std::unique_ptr<CanopenBench> inner_;
};

class InProcessSimulatedBench final : public ForwardingBench, public SimulatedBenchAccess {
 public:
  explicit InProcessSimulatedBench(const BenchConfig& source) : config_(source) {
    auto devices = simulated_devices_from(config_);
    true_gear_ = devices.gear;
    encoder_noise_ = devices.encoder.noise_rad;
    torque_noise_ = devices.torque_sensor.noise_nm;

    if (config_.simulated->brake_server) {
      simdevices::BrakeServerOptions brake;
      brake.endpoint.transport = modbus::Transport::tcp;
      brake.endpoint.host = "127.0.0.1";
      brake.endpoint.port = 0;
      brake.unit_id = config_.brake.link.unit_id;
      brake.real_time = false;  // the plant steps the brake physics in bench time
      // Loopback on an ephemeral port is still open to every local user: writes need a secret
      // only this bench's brake client knows (brake_registers::unlock).
      brake.unlock_secret = simdevices::random_unlock_secret();
      brake_ = simdevices::start_brake_server(brake);
      config_.brake.link.endpoint = brake.endpoint;
      config_.brake.link.endpoint.port = brake_->port();
      config_.brake.link.unlock_secret = brake.unlock_secret;
    }

    virtual_bus_ = std::make_unique<can::VirtualCanBus>(io_);
    virtual_bus_->record(false);
    device_endpoint_ = virtual_bus_->endpoint("simulated devices");
    master_endpoint_ = virtual_bus_->endpoint("master");
    devices_ = std::make_unique<simdevices::SimulatedBench>(devices, *device_endpoint_);
    if (auto* server = brake_.get()) {
      devices_->set_brake_coupling([server](double omega_out, double dt) {
        server->set_output_speed(omega_out);
        server->step(dt);
        return server->with_controller(
            [](simdevices::PowderBrakeController& c) { return c.physics().torque_capacity(); });
      });
    }
    devices_->start();
    inner_ = std::make_unique<CanopenBench>(config_, *master_endpoint_);
  }
  ~InProcessSimulatedBench() override {
    inner_.reset();
    devices_.reset();
    if (brake_) brake_->stop();
  }

  const model::GearParams& true_gear() const override { return true_gear_; }
  double encoder_noise_rad() const override { return encoder_noise_; }
  double torque_noise_nm() const override { return torque_noise_; }
  simdevices::SimulatedBench& devices() override { return *devices_; }
  simdevices::BrakeServer& brake_server() override {
    if (!brake_) throw std::logic_error("this simulated bench has no brake server");
    return *brake_;
  }
  CanopenBench& canopen() override { return *inner_; }
  can::VirtualCanBus& virtual_bus() override { return *virtual_bus_; }

 private:
  BenchConfig config_;
  model::GearParams true_gear_;
  double encoder_noise_ = 0;
  double torque_noise_ = 0;
  boost::asio::io_context io_;
  std::unique_ptr<simdevices::BrakeServer> brake_;
  std::unique_ptr<can::VirtualCanBus> virtual_bus_;
  std::unique_ptr<can::VirtualCanEndpoint> device_endpoint_;
  std::unique_ptr<can::VirtualCanEndpoint> master_endpoint_;
  std::unique_ptr<simdevices::SimulatedBench> devices_;
};

class SocketCanBench final : public ForwardingBench {
 public:
  explicit SocketCanBench(const BenchConfig& config)
      : bus_(std::make_unique<can::SocketCanBus>(io_, config.can.interface)) {
    inner_ = std::make_unique<CanopenBench>(config, *bus_);
  }
  ~SocketCanBench() override { inner_.reset(); }

 private:
  boost::asio::io_context io_;
  std::unique_ptr<can::SocketCanBus> bus_;
};

}  // namespace

simdevices::SimulatedBenchConfig simulated_devices_from(const BenchConfig& config) {
  auto devices = config.simulated && config.simulated->devices ? *config.simulated->devices
                                                               : simdevices::SimulatedBenchConfig{};
  devices.gear = true_gear_from(config);
  devices.clock = config.description.simulated_clock ? simdevices::BenchClock::kSyncDriven
                                                     : simdevices::BenchClock::kRealTime;
  devices.sync_period = config.description.sync_period_s;
  devices.drive.node_id = config.simulated->drive_node.value_or(config.can.drive_node);
  devices.drive.counts_per_revolution = config.drive.counts_per_revolution;
  devices.encoder.node_id = config.simulated->encoder_node.value_or(config.can.encoder_node);
  if (config.encoder.counts_per_turn)
    devices.encoder.single_turn_resolution = *config.encoder.counts_per_turn;
  if (config.encoder.turns)
    devices.encoder.revolutions = static_cast<std::uint16_t>(*config.encoder.turns);
  if (config.encoder.noise_rad > 0) devices.encoder.noise_rad = config.encoder.noise_rad;
  devices.torque_sensor.node_id = config.simulated->torque_node.value_or(config.can.torque_node);
  devices.torque_sensor.index = config.torque_sensor.sensor.index;
  devices.torque_sensor.sub = config.torque_sensor.sensor.sub;
  devices.torque_sensor.scale_nm_per_unit = config.torque_sensor.sensor.scale;
  if (config.torque_sensor.noise_nm > 0)
    devices.torque_sensor.noise_nm = config.torque_sensor.noise_nm;
  return devices;
}

model::GearParams true_gear_from(const BenchConfig& config) {
  if (!config.simulated)
    throw config::ConfigError("simulated", "(missing)", "a simulated section for a simulated bench",
                              config.source);
  const auto& s = *config.simulated;
  model::GearParams gear;
  try {
    gear = config::load_twin_case(s.true_gear_case).gear;
  } catch (const config::ConfigError& e) {
    throw config::ConfigError("simulated.true_gear.case", s.true_gear_case.string(),
                              std::string("a twin case: ") + e.what(), config.source);
  }
  const auto& v = s.variation;
  for (auto& term : gear.te_terms) {
    term.amplitude_rad *= v.te_amplitude_scale;
    term.phase_rad += v.te_phase_shift_rad;
  }
  if (v.stiffness_scale != 1.0) model::scale_stiffness(gear.stiffness, v.stiffness_scale);
  if (v.backlash_rad) gear.backlash.total_rad = *v.backlash_rad;
  const double ratio = config.description.sense.ratio;
  if (std::abs(gear.geometry.ratio - ratio) > 1e-9 * ratio) {
    throw config::ConfigError("simulated.true_gear.case", s.true_gear_case.string(),
                              "a gear of ratio " + std::to_string(ratio) + " (gear.ratio), not " +
                                  std::to_string(gear.geometry.ratio),
                              config.source);
  }
  // How the unit is mounted on this bench is the bench's, not the gear case's.
  gear.geometry.direction_sign = config.description.sense.direction_sign;
  gear.name += " (simulated unit, true parameters)";
  return gear;
}

std::unique_ptr<Bench> make_simulated_bench(const BenchConfig& config) {
  return std::make_unique<InProcessSimulatedBench>(config);
}

std::unique_ptr<Bench> make_bench(const BenchConfig& config) {
  if (config.in_process()) return make_simulated_bench(config);
  return std::make_unique<SocketCanBench>(config);
}

CanopenBench* canopen_bench_of(Bench& bench) {
  auto* forwarding = dynamic_cast<ForwardingBench*>(&bench);
  return forwarding ? &forwarding->canopen_bench() : dynamic_cast<CanopenBench*>(&bench);
}

SimulatedBenchAccess* simulated_access(Bench& bench) {
  return dynamic_cast<SimulatedBenchAccess*>(&bench);
}

}  // namespace wavebench::bench
