// A torque sensor as a bench device: one torque channel [N*m] from its configured object in
// TPDO1, scaled by the sensor's config (canopen::TorqueSensor).
#include "device_kinds.hpp"

namespace wavebench::bench {
namespace {

class TorqueSensorDevice final : public CanopenDevice {
 public:
  TorqueSensorDevice(std::string name, const ChannelDeviceSettings& s)
      : CanopenDevice(std::move(name), s.node),
        settings_(s),
        layout_({canopen::PdoEntry::decode(mapping_entry(s.torque))}) {}

  std::vector<storage::ChannelInfo> channels() const override {
    return {{settings_.channel, "N*m"}};
  }
  std::vector<canopen::UsedObject> used_objects() const override {
    return canopen::TorqueSensor::used_objects(settings_.torque);
  }

  void configure(canopen::SdoClient& sdo) override {
    sensor_ = std::make_unique<canopen::TorqueSensor>(sdo, settings_.torque);
    canopen::configure_pdo(sdo, canopen::PdoDirection::transmit, 1, tpdos().front());
  }

  std::vector<canopen::PdoConfig> tpdos() const override {
    return {{canopen::tpdo_cob_id(1, node()), 1, 0, layout_.entries()}};
  }

  bool on_pdo(std::size_t i, const can::Frame& frame, CycleRecord& record) noexcept override {
    if (i != 0 || !sensor_ || !layout_.fits(frame)) return false;
    put(record, 0, settings_.sign * sensor_->torque_from_raw(layout_.raw(frame, 0)));
    return true;
  }

 private:
  static std::uint32_t mapping_entry(const canopen::TorqueSensorConfig& c) {
    return static_cast<std::uint32_t>(c.index) << 16 | static_cast<std::uint32_t>(c.sub) << 8 |
           static_cast<std::uint32_t>(canopen::size_of(c.type) * 8);
  }

  ChannelDeviceSettings settings_;
  canopen::PdoLayout layout_;
  std::unique_ptr<canopen::TorqueSensor> sensor_;
};

}  // namespace

ChannelDeviceKind torque_sensor_kind() {
  return {"torque_sensor",
          "a torque sensor; its torque [N*m] from the configured object in TPDO1",
          {"object", "type", "scale", "offset"},
          [](std::string name, const ChannelDeviceSettings& s) -> std::unique_ptr<CanopenDevice> {
            return std::make_unique<TorqueSensorDevice>(std::move(name), s);
          }};
}

}  // namespace wavebench::bench
