// A torque sensor as a channel device: its configured object in TPDO1, scaled to N*m.
#include "channel_device_kinds.hpp"
#include "wavebench/canopen/cob_id.hpp"

namespace wavebench::bench {
namespace {

class TorqueChannelDevice final : public ChannelDevice {
 public:
  explicit TorqueChannelDevice(const ChannelDeviceSettings& s)
      : ChannelDevice(s), layout_({canopen::PdoEntry::decode(mapping_entry(s.torque))}) {}

  storage::ChannelInfo channel() const override { return {settings().channel, "N*m"}; }

  void configure(canopen::SdoClient& sdo) override {
    sensor_ = std::make_unique<canopen::TorqueSensor>(sdo, settings().torque);
  }

  canopen::PdoConfig tpdo() const override {
    return {canopen::tpdo_cob_id(1, node()),
            1,
            0,
            {canopen::PdoEntry::decode(mapping_entry(settings().torque))}};
  }

  std::optional<double> on_pdo(const can::Frame& frame) noexcept override {
    if (!sensor_ || !layout_.fits(frame)) return std::nullopt;
    return settings().sign * sensor_->torque_from_raw(layout_.raw(frame, 0));
  }

 private:
  static std::uint32_t mapping_entry(const canopen::TorqueSensorConfig& c) {
    return static_cast<std::uint32_t>(c.index) << 16 | static_cast<std::uint32_t>(c.sub) << 8 |
           static_cast<std::uint32_t>(canopen::size_of(c.type) * 8);
  }

  canopen::PdoLayout layout_;
  std::unique_ptr<canopen::TorqueSensor> sensor_;
};

}  // namespace

ChannelDeviceKind torque_sensor_kind() {
  return {"torque_sensor",
          "a torque sensor; its torque [N*m] from the configured object in TPDO1",
          {"object", "type", "scale", "offset"},
          [](const ChannelDeviceSettings& s) { return std::make_unique<TorqueChannelDevice>(s); }};
}

}  // namespace wavebench::bench
