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
        entry_(canopen::PdoEntry::decode(mapping_entry(s.torque))) {}

  std::vector<storage::ChannelInfo> channels() const override {
    return {{settings_.channel, "N*m"}};
  }
  std::vector<canopen::UsedObject> used_objects() const override {
    return canopen::TorqueSensor::used_objects(settings_.torque);
  }

  void configure(canopen::SdoClient& sdo) override {
    sensor_ = std::make_unique<canopen::TorqueSensor>(sdo, settings_.torque);
    adopted_ = {};
    const canopen::NeededObject needed[] = {{entry_.index, entry_.sub, entry_.bits, "torque"}};
    adopt_tpdos(sdo, {bench_tpdo()}, needed);
  }

  std::vector<canopen::PdoConfig> tpdos() const override {
    if (!adopted_.pdos().empty()) return adopted_.configs();
    return {bench_tpdo()};
  }

  bool on_pdo(std::size_t i, const can::Frame& frame, CycleRecord& record) noexcept override {
    if (!sensor_) return false;
    // The torque object wherever the device maps it (a fixed mapping: as found).
    const auto raw = adopted_.raw(0, i, frame);
    if (!raw) return false;
    put(record, 0, settings_.sign * sensor_->torque_from_raw(*raw));
    return true;
  }

 private:
  static std::uint32_t mapping_entry(const canopen::TorqueSensorConfig& c) {
    return static_cast<std::uint32_t>(c.index) << 16 | static_cast<std::uint32_t>(c.sub) << 8 |
           static_cast<std::uint32_t>(canopen::size_of(c.type) * 8);
  }

  canopen::PdoConfig bench_tpdo() const {
    return {canopen::tpdo_cob_id(1, node()), 1, 0, {entry_}};
  }

  ChannelDeviceSettings settings_;
  canopen::PdoEntry entry_;
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
