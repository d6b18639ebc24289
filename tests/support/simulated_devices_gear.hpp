#pragma once
// The simulated devices' default unit, as `wavebench simbench` loads it without --gear: the
// shipped twin case configs/benches/simulated-devices-gear.yaml (issue #23: the simulated unit
// is a twin case; its numbers are not written in C++). Tests that link wavebench_config.

#include "wavebench/config/twin_case.hpp"
#include "wavebench/model/gear_params.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"

namespace wavebench::testing {

inline const model::GearParams& simulated_devices_gear() {
  static const model::GearParams gear =
      config::load_twin_case(std::string(WAVEBENCH_SOURCE_DIR) +
                             "/configs/benches/simulated-devices-gear.yaml")
          .gear;
  return gear;
}

// The simulated devices' defaults with that gear.
inline simdevices::SimulatedBenchConfig simulated_devices_config() {
  simdevices::SimulatedBenchConfig config;
  config.gear = simulated_devices_gear();
  return config;
}

}  // namespace wavebench::testing
