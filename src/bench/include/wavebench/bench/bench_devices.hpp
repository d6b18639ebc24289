#pragma once
// The CANopen devices of a bench config, each with its node, the objects the bench uses on it
// (from its driver class in drivers/canopen) and what the config expects of it (EDS, identity).
// The EDS check before connecting and the commissioning check walk this one list.

#include <cstdint>
#include <string>
#include <vector>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/canopen/used_object.hpp"

namespace wavebench::bench {

struct BenchCanopenDevice {
  std::string name;        // "servo drive"
  std::string config_key;  // "drive": the config section naming its eds and identity
  std::uint8_t node = 0;
  std::uint16_t profile = 0;  // CiA device profile in 0x1000's low word; 0: none required
  std::vector<canopen::UsedObject> used;
  const NodeExpectations* expect = nullptr;  // points into the config
};

std::vector<BenchCanopenDevice> canopen_devices(const BenchConfig& config);

// Each device's used objects against its EDS, one line per disagreement naming the device and
// the file; empty when every named EDS agrees (or none is named).
std::vector<std::string> eds_problems(const BenchConfig& config);

}  // namespace wavebench::bench
