#include "channel_device_kinds.hpp"
#include "wavebench/bench/channel_device.hpp"

namespace wavebench::bench {

std::string ChannelDevice::describe() const {
  return settings_.kind + " '" + settings_.channel + "' (node " + std::to_string(settings_.node) +
         ")";
}

const std::vector<ChannelDeviceKind>& channel_device_kinds() {
  static const std::vector<ChannelDeviceKind> kinds{
      cia406_encoder_kind(),
      torque_sensor_kind(),
  };
  return kinds;
}

const ChannelDeviceKind* find_channel_device_kind(const std::string& kind) {
  for (const auto& k : channel_device_kinds())
    if (k.kind == kind) return &k;
  return nullptr;
}

}  // namespace wavebench::bench
