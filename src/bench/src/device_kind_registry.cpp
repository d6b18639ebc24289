#include "device_kinds.hpp"
#include "wavebench/bench/channel_device.hpp"

namespace wavebench::bench {

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

std::unique_ptr<CanopenDevice> make_channel_device(const ChannelDeviceSettings& settings) {
  const auto* kind = find_channel_device_kind(settings.kind);
  if (!kind)
    throw std::invalid_argument("bench device '" + settings.channel + "': unknown kind " +
                                settings.kind);
  return kind->make(settings.kind + " '" + settings.channel + "'", settings);
}

}  // namespace wavebench::bench
