#pragma once
// A torque sensor node whose process value is one mapped object: which object, its data type
// and its scale to N·m come from configuration, not from a device profile.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>
#include <system_error>

#include "wavebench/canopen/sdo_client.hpp"
#include "wavebench/canopen/used_object.hpp"

namespace wavebench::canopen {

enum class ValueType { u8, u16, u32, u64, i8, i16, i32, i64, f32, f64 };

std::optional<ValueType> parse_value_type(std::string_view text) noexcept;
std::string_view to_string(ValueType type) noexcept;
std::size_t size_of(ValueType type) noexcept;
// The CiA 301 data type index (datatype::kInteger32 for i32, ...).
std::uint16_t data_type_of(ValueType type) noexcept;
// The little-endian bytes as a double (integers exactly up to 2^53); nullopt on a size mismatch.
std::optional<double> decode_number(ValueType type, std::span<const std::uint8_t> bytes) noexcept;

struct TorqueSensorConfig {
  std::uint16_t index = 0x6000;  // no profile fixes these: the config must
  std::uint8_t sub = 1;
  ValueType type = ValueType::i32;
  double scale = 1e-3;  // N·m per raw unit
  double offset = 0.0;  // N·m added after scaling
};

class TorqueSensor {
 public:
  TorqueSensor(SdoClient& sdo, TorqueSensorConfig config);
  TorqueSensor(const TorqueSensor&) = delete;
  TorqueSensor& operator=(const TorqueSensor&) = delete;

  // Every object the bench uses on a torque sensor whose process value is `config`'s object.
  static std::vector<UsedObject> used_objects(const TorqueSensorConfig& config);

  const TorqueSensorConfig& config() const noexcept { return config_; }
  // The PDO mapping entry for the configured object.
  std::uint32_t mapping_entry() const noexcept;
  // Torque [N·m] from the raw bytes of a PDO slot or SDO upload; nullopt on size mismatch.
  std::optional<double> torque_from(std::span<const std::uint8_t> raw) const noexcept;
  double torque_from_raw(std::uint64_t raw) const noexcept;  // a PdoLayout::raw value
  double read_torque();                                      // by SDO
  double read_torque(std::error_code& ec) noexcept;

 private:
  SdoClient& sdo_;
  TorqueSensorConfig config_;
};

}  // namespace wavebench::canopen
