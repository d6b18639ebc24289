#include "wavebench/bench/bench_devices.hpp"

#include "wavebench/bench/channel_device.hpp"

namespace wavebench::bench {

BenchDeviceSet make_bench_devices(const BenchConfig& config) {
  BenchDeviceSet set;
  set.drive = std::make_unique<Cia402DriveDevice>(config.can.drive_node, config.drive);
  ChannelDeviceSettings encoder;
  encoder.channel = "theta_out";
  encoder.kind = "cia406_encoder";
  encoder.node = config.can.encoder_node;
  encoder.counts_per_turn = config.encoder.counts_per_turn;
  encoder.turns = config.encoder.turns;
  set.sensors.push_back(
      find_channel_device_kind("cia406_encoder")->make("output encoder", encoder));
  ChannelDeviceSettings torque;
  torque.channel = "torque";
  torque.kind = "torque_sensor";
  torque.node = config.can.torque_node;
  torque.torque = config.torque_sensor.sensor;
  set.sensors.push_back(find_channel_device_kind("torque_sensor")->make("torque sensor", torque));
  for (const auto& d : config.devices) set.sensors.push_back(make_channel_device(d));
  return set;
}

std::vector<BenchCanopenDevice> canopen_devices(const BenchConfig& config) {
  const auto set = make_bench_devices(config);
  const CanopenDevice* core[] = {set.drive.get(), set.sensors[0].get(), set.sensors[1].get()};
  const char* keys[] = {"drive", "encoder", "torque_sensor"};
  const NodeExpectations* expect[] = {&config.drive.expect, &config.encoder.expect,
                                      &config.torque_sensor.expect};
  std::vector<BenchCanopenDevice> out;
  for (std::size_t i = 0; i < 3; ++i)
    out.push_back({core[i]->name(), keys[i], core[i]->node(), core[i]->profile(),
                   core[i]->used_objects(), core[i]->tpdos(), expect[i]});
  return out;
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
