#pragma once
// The devices of a bench config: made here once (make_bench_devices) for the bench and for the
// checks that need them before a bench exists. The EDS check before connecting and the
// commissioning check walk the core CANopen devices with what the config expects of each (EDS,
// identity).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/cia402_drive_device.hpp"
#include "wavebench/canopen/used_object.hpp"

namespace wavebench::bench {

struct BenchDeviceSet {
  std::unique_ptr<Cia402DriveDevice> drive;
  // The output encoder (channel theta_out), the torque sensor (channel torque), then the
  // config's `devices:` in order (the extra channels).
  std::vector<std::unique_ptr<CanopenDevice>> sensors;
};
// Throws std::invalid_argument for a `devices:` kind the registry does not know.
BenchDeviceSet make_bench_devices(const BenchConfig& config);

struct BenchCanopenDevice {
  std::string name;        // "servo drive"
  std::string config_key;  // "drive": the config section naming its eds and identity
  std::uint8_t node = 0;
  std::uint16_t profile = 0;  // CiA device profile in 0x1000's low word; 0: none required
  std::vector<canopen::UsedObject> used;
  std::vector<canopen::PdoConfig> tpdos;     // as the bench maps them (drive: with 0x60F4)
  const NodeExpectations* expect = nullptr;  // points into the config
};

// The drive, the output encoder and the torque sensor.
std::vector<BenchCanopenDevice> canopen_devices(const BenchConfig& config);

// Each device's used objects against its EDS, one line per disagreement naming the device and
// the file; empty when every named EDS agrees (or none is named).
std::vector<std::string> eds_problems(const BenchConfig& config);

}  // namespace wavebench::bench
