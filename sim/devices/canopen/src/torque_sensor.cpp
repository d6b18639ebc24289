#include "wavebench/simdevices/torque_sensor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace wavebench::simdevices {

TorqueSensor::TorqueSensor(const TorqueSensorConfig& config, FrameSink sink)
    : CanopenNode(config.node_id, config.identity, std::move(sink)),
      config_(config),
      rng_(config.seed) {
  if (config.type != DataType::kInteger16 && config.type != DataType::kInteger32 &&
      config.type != DataType::kReal32) {
    throw std::invalid_argument("torque sensor: type " +
                                std::to_string(static_cast<unsigned>(config.type)) +
                                " is not supported (expected INTEGER16, INTEGER32 or REAL32)");
  }
  if (!(config.scale_nm_per_unit > 0)) {
    throw std::invalid_argument("torque sensor: scale " + std::to_string(config.scale_nm_per_unit) +
                                " must be > 0 (N*m per unit)");
  }
  if (config.index < 0x2000) {
    throw std::invalid_argument("torque sensor: index " + std::to_string(config.index) +
                                " is in the communication area (expected >= 0x2000)");
  }
  if (config.sub != 0) {
    od().add_value<std::uint8_t>(config.index, 0, "highest sub-index", DataType::kUnsigned8,
                                 Access::kConst, config.sub);
  }
  od().add(config.index, config.sub, "torque process value", config.type, Access::kReadOnly,
           std::vector<std::uint8_t>(data_type_size(config.type)), true);
  od().add_value<float>(0x2100, 0, "torque scale [N*m per unit]", DataType::kReal32,
                        Access::kReadOnly, static_cast<float>(config.scale_nm_per_unit));
  set_default_tpdo(
      1, {{config.index, config.sub, static_cast<std::uint8_t>(8 * data_type_size(config.type))}},
      true, 1);
  for (const auto& fixed : config.fixed_tpdos) fix_tpdo(fixed);
  observe(0);
}

void TorqueSensor::observe(double torque_nm) {
  const double measured = torque_nm + config_.offset_nm + config_.noise_nm * noise_(rng_);
  const double units = measured / config_.scale_nm_per_unit;
  switch (config_.type) {
    case DataType::kInteger16:
      od().set<std::int16_t>(
          config_.index, config_.sub,
          static_cast<std::int16_t>(std::clamp(std::round(units), -32768.0, 32767.0)));
      break;
    case DataType::kInteger32:
      od().set<std::int32_t>(
          config_.index, config_.sub,
          static_cast<std::int32_t>(std::clamp(std::round(units), -2147483648.0, 2147483647.0)));
      break;
    default:
      od().set<float>(config_.index, config_.sub, static_cast<float>(units));
      break;
  }
}

double TorqueSensor::value_nm() const {
  switch (config_.type) {
    case DataType::kInteger16:
      return od().get<std::int16_t>(config_.index, config_.sub) * config_.scale_nm_per_unit;
    case DataType::kInteger32:
      return od().get<std::int32_t>(config_.index, config_.sub) * config_.scale_nm_per_unit;
    default:
      return static_cast<double>(od().get<float>(config_.index, config_.sub)) *
             config_.scale_nm_per_unit;
  }
}

}  // namespace wavebench::simdevices
