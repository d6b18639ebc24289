#pragma once
// The CANopen devices a bench config adds under `devices:` (an input-side CiA 406 encoder as in
// seed 004's bench, a second torque sensor), each recorded as one extra channel of the sample
// and the sample log. Each is a CanopenDevice (bench_device.hpp) made by the registry below; a
// new kind is one file (device_<kind>.cpp) and one line in device_kind_registry.cpp. The core
// output encoder and torque sensor are devices of the same kinds.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/bench/bench_device.hpp"
#include "wavebench/canopen/torque_sensor.hpp"

namespace wavebench::bench {

// One entry of the bench config's `devices:` (see configs/benches/README.md), or a core device.
struct ChannelDeviceSettings {
  std::string channel;  // the key under devices: and the channel's name
  std::string kind;     // a key of the registry: cia406_encoder, torque_sensor
  std::uint8_t node = 0;
  int sign = 1;  // -1: the device counts against the bench's positive direction
  // cia406_encoder: unset reads 0x6501 / 0x6502.
  std::optional<std::uint32_t> counts_per_turn;
  std::optional<std::uint32_t> turns;
  // torque_sensor: the object, type, scale and offset of its torque.
  canopen::TorqueSensorConfig torque{0x6130, 1, canopen::ValueType::i32, 1e-3, 0.0};
};

struct ChannelDeviceKind {
  std::string kind;
  std::string description;
  // The keys its settings may have beside kind, node and sign (for the config's key check).
  std::vector<std::string> keys;
  // `name` is the device's name in messages ("output encoder"; for `devices:` entries
  // "<kind> '<channel>'").
  std::function<std::unique_ptr<CanopenDevice>(std::string name, const ChannelDeviceSettings&)>
      make;
};

// Every kind of channel device, by name.
const std::vector<ChannelDeviceKind>& channel_device_kinds();
const ChannelDeviceKind* find_channel_device_kind(const std::string& kind);
// A `devices:` entry's device, named "<kind> '<channel>'". Throws std::invalid_argument for an
// unknown kind.
std::unique_ptr<CanopenDevice> make_channel_device(const ChannelDeviceSettings& settings);

}  // namespace wavebench::bench
