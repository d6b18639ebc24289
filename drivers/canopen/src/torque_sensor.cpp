#include "wavebench/canopen/torque_sensor.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace wavebench::canopen {

namespace {

template <typename T>
double as(std::span<const std::uint8_t> bytes) noexcept {
  T v{};
  std::memcpy(&v, bytes.data(), sizeof(T));
  return static_cast<double>(v);
}

}  // namespace

std::optional<ValueType> parse_value_type(std::string_view text) noexcept {
  for (auto t : {ValueType::u8, ValueType::u16, ValueType::u32, ValueType::u64, ValueType::i8,
                 ValueType::i16, ValueType::i32, ValueType::i64, ValueType::f32, ValueType::f64}) {
    if (text == to_string(t)) return t;
  }
  return std::nullopt;
}

std::string_view to_string(ValueType type) noexcept {
  switch (type) {
    case ValueType::u8:
      return "u8";
    case ValueType::u16:
      return "u16";
    case ValueType::u32:
      return "u32";
    case ValueType::u64:
      return "u64";
    case ValueType::i8:
      return "i8";
    case ValueType::i16:
      return "i16";
    case ValueType::i32:
      return "i32";
    case ValueType::i64:
      return "i64";
    case ValueType::f32:
      return "f32";
    case ValueType::f64:
      return "f64";
  }
  return "?";
}

std::size_t size_of(ValueType type) noexcept {
  switch (type) {
    case ValueType::u8:
    case ValueType::i8:
      return 1;
    case ValueType::u16:
    case ValueType::i16:
      return 2;
    case ValueType::u32:
    case ValueType::i32:
    case ValueType::f32:
      return 4;
    case ValueType::u64:
    case ValueType::i64:
    case ValueType::f64:
      return 8;
  }
  return 0;
}

std::optional<double> decode_number(ValueType type, std::span<const std::uint8_t> b) noexcept {
  if (b.size() != size_of(type)) return std::nullopt;
  switch (type) {
    case ValueType::u8:
      return as<std::uint8_t>(b);
    case ValueType::u16:
      return as<std::uint16_t>(b);
    case ValueType::u32:
      return as<std::uint32_t>(b);
    case ValueType::u64:
      return as<std::uint64_t>(b);
    case ValueType::i8:
      return as<std::int8_t>(b);
    case ValueType::i16:
      return as<std::int16_t>(b);
    case ValueType::i32:
      return as<std::int32_t>(b);
    case ValueType::i64:
      return as<std::int64_t>(b);
    case ValueType::f32:
      return as<float>(b);
    case ValueType::f64:
      return as<double>(b);
  }
  return std::nullopt;
}

namespace {
using enum UsedAccess;
using enum UsedInPdo;
namespace dt = datatype;

constexpr auto kTorqueSensorNodeObjects = node_objects();

}  // namespace

std::uint16_t data_type_of(ValueType type) noexcept {
  switch (type) {
    case ValueType::u8:
      return datatype::kUnsigned8;
    case ValueType::u16:
      return datatype::kUnsigned16;
    case ValueType::u32:
      return datatype::kUnsigned32;
    case ValueType::u64:
      return datatype::kUnsigned64;
    case ValueType::i8:
      return datatype::kInteger8;
    case ValueType::i16:
      return datatype::kInteger16;
    case ValueType::i32:
      return datatype::kInteger32;
    case ValueType::i64:
      return datatype::kInteger64;
    case ValueType::f32:
      return datatype::kReal32;
    case ValueType::f64:
      return datatype::kReal64;
  }
  return 0;
}

std::vector<UsedObject> TorqueSensor::used_objects(const TorqueSensorConfig& config) {
  std::vector<UsedObject> out(std::begin(kTorqueSensorNodeObjects),
                              std::end(kTorqueSensorNodeObjects));
  out.push_back({config.index, config.sub, "torque process value", data_type_of(config.type), 0,
                 kRead, kTpdo});
  return out;
}

TorqueSensor::TorqueSensor(SdoClient& sdo, TorqueSensorConfig config) : sdo_(sdo), config_(config) {
  if (!std::isfinite(config_.scale) || config_.scale == 0.0) {
    throw std::invalid_argument("torque sensor scale " + std::to_string(config_.scale) +
                                ": expected a finite non-zero N·m per unit");
  }
}

std::uint32_t TorqueSensor::mapping_entry() const noexcept {
  return static_cast<std::uint32_t>(config_.index) << 16 |
         static_cast<std::uint32_t>(config_.sub) << 8 |
         static_cast<std::uint32_t>(size_of(config_.type) * 8);
}

std::optional<double> TorqueSensor::torque_from(std::span<const std::uint8_t> raw) const noexcept {
  const auto v = decode_number(config_.type, raw);
  if (!v) return std::nullopt;
  return *v * config_.scale + config_.offset;
}

double TorqueSensor::torque_from_raw(std::uint64_t raw) const noexcept {
  std::uint8_t bytes[8];
  std::memcpy(bytes, &raw, 8);
  return *torque_from(std::span<const std::uint8_t>(bytes, size_of(config_.type)));
}

double TorqueSensor::read_torque(std::error_code& ec) noexcept {
  const auto bytes = sdo_.upload(config_.index, config_.sub, ec);
  if (ec) return 0.0;
  const auto t = torque_from(bytes);
  if (!t) {
    ec = make_error_code(SdoAbort::length_mismatch);
    return 0.0;
  }
  return *t;
}

double TorqueSensor::read_torque() {
  std::error_code ec;
  const double t = read_torque(ec);
  if (ec) throw SdoError(ec, sdo_.node(), config_.index, config_.sub);
  return t;
}

}  // namespace wavebench::canopen
