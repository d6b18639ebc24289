#include "wavebench/bench/bench_devices.hpp"

#include "wavebench/canopen/cia402_drive.hpp"
#include "wavebench/canopen/cia406_encoder.hpp"
#include "wavebench/canopen/torque_sensor.hpp"

namespace wavebench::bench {

std::vector<BenchCanopenDevice> canopen_devices(const BenchConfig& config) {
  const auto drive = canopen::Cia402Drive::used_objects();
  const auto encoder = canopen::Cia406Encoder::used_objects();
  return {
      {"servo drive",
       "drive",
       config.can.drive_node,
       0x0192,
       {drive.begin(), drive.end()},
       &config.drive.expect},
      {"output encoder",
       "encoder",
       config.can.encoder_node,
       0x0196,
       {encoder.begin(), encoder.end()},
       &config.encoder.expect},
      {"torque sensor", "torque_sensor", config.can.torque_node, 0,
       canopen::TorqueSensor::used_objects(config.torque_sensor.sensor),
       &config.torque_sensor.expect},
  };
}

std::vector<std::string> eds_problems(const BenchConfig& config) {
  std::vector<std::string> out;
  for (const auto& device : canopen_devices(config)) {
    if (!device.expect->eds) continue;
    for (const auto& problem : canopen::check_against_eds(device.used, *device.expect->eds)) {
      out.push_back(device.name + " (" + device.config_key +
                    ".eds = " + device.expect->eds_path.filename().string() + "): " + problem);
    }
  }
  return out;
}

}  // namespace wavebench::bench
