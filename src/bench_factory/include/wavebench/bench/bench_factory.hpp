#pragma once
// Benches from a BenchConfig: the in-process simulated bench (bench.md §6) or CANopen on a
// SocketCAN interface (real hardware, or `wavebench simbench` as its own process).

#include <memory>

#include "wavebench/bench/bench.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/model/gear_params.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"

namespace wavebench::can {
class VirtualCanBus;
}  // namespace wavebench::can

namespace wavebench::simdevices {
class BrakeServer;
}  // namespace wavebench::simdevices

namespace wavebench::bench {

class CanopenBench;

// What tests and truth computations may see of the in-process simulated bench. Everything here
// lives on the bench thread (the simulated devices run on the bench's io_context).
class SimulatedBenchAccess {
 public:
  virtual ~SimulatedBenchAccess() = default;
  // The simulated unit's own ("true") gear: not the twin's nominal one.
  virtual const model::GearParams& true_gear() const = 0;
  virtual double encoder_noise_rad() const = 0;  // 1-sigma of the simulated output encoder
  virtual double torque_noise_nm() const = 0;    // 1-sigma of the simulated torque sensor
  // Plant (truth: angles, twist, torques), servo drive, encoder, torque sensor.
  virtual simdevices::SimulatedBench& devices() = 0;
  // The simulated brake controller (with_controller(), inject_fault(), stop()).
  virtual simdevices::BrakeServer& brake_server() = 0;
  virtual CanopenBench& canopen() = 0;
  // The in-process bus; record(true) keeps every frame in log() for tests that check frames.
  virtual can::VirtualCanBus& virtual_bus() = 0;
};

// The simulated unit's true gear: the case named in simulated.true_gear, varied as configured.
model::GearParams true_gear_from(const BenchConfig& config);
// The simulated devices of a simulated bench config (true gear, nodes, resolutions, noise, clock),
// the same for the in-process bench and `wavebench simbench --bench-config`. Throws
// config::ConfigError when the config has no simulated section.
simdevices::SimulatedBenchConfig simulated_devices_from(const BenchConfig& config);

// In-process: an io_context, a virtual CAN bus, the simulated devices (SYNC-driven on the
// simulated clock, real time otherwise) and the brake controller on loopback TCP, coupled to
// the plant; the daemon's CANopen master and Modbus client talk to them as to hardware.
// The returned bench also implements SimulatedBenchAccess (see simulated_access()).
std::unique_ptr<Bench> make_simulated_bench(const BenchConfig& config);
// In-process when config.can.interface is "inproc", else CANopen on that SocketCAN interface
// with the brake at config.brake.link.endpoint.
std::unique_ptr<Bench> make_bench(const BenchConfig& config);

// The CanopenBench inside a bench from make_bench() (or `bench` itself); nullptr otherwise.
CanopenBench* canopen_bench_of(Bench& bench);

// nullptr for anything but the in-process simulated bench.
SimulatedBenchAccess* simulated_access(Bench& bench);

}  // namespace wavebench::bench
