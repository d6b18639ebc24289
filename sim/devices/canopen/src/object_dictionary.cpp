#include "wavebench/simdevices/object_dictionary.hpp"

#include <cstdio>

#include "wavebench/simdevices/sdo_abort.hpp"

namespace wavebench::simdevices {
namespace {

std::string hex_address(std::uint16_t index, std::uint8_t sub) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04X:%02X", static_cast<unsigned>(index),
                static_cast<unsigned>(sub));
  return buf;
}

bool is_signed(DataType type) {
  return type == DataType::kInteger8 || type == DataType::kInteger16 ||
         type == DataType::kInteger32 || type == DataType::kInteger64;
}

bool is_integer(DataType type) {
  switch (type) {
    case DataType::kBoolean:
    case DataType::kInteger8:
    case DataType::kInteger16:
    case DataType::kInteger32:
    case DataType::kInteger64:
    case DataType::kUnsigned8:
    case DataType::kUnsigned16:
    case DataType::kUnsigned32:
    case DataType::kUnsigned64:
      return true;
    default:
      return false;
  }
}

std::int64_t decode_integer(DataType type, std::span<const std::uint8_t> data) {
  const std::size_t n = data_type_size(type);
  std::uint64_t raw = 0;
  for (std::size_t i = 0; i < n && i < data.size(); ++i) {
    raw |= static_cast<std::uint64_t>(data[i]) << (8 * i);
  }
  if (is_signed(type) && n < 8 && (raw >> (8 * n - 1)) & 1U) {
    raw |= ~std::uint64_t{0} << (8 * n);  // sign-extend
  }
  return static_cast<std::int64_t>(raw);
}

}  // namespace

std::size_t data_type_size(DataType type) {
  switch (type) {
    case DataType::kBoolean:
    case DataType::kInteger8:
    case DataType::kUnsigned8:
      return 1;
    case DataType::kInteger16:
    case DataType::kUnsigned16:
      return 2;
    case DataType::kInteger32:
    case DataType::kUnsigned32:
    case DataType::kReal32:
      return 4;
    case DataType::kInteger64:
    case DataType::kUnsigned64:
    case DataType::kReal64:
      return 8;
    case DataType::kVisibleString:
      return 0;
  }
  return 0;
}

OdEntry& ObjectDictionary::add(std::uint16_t index, std::uint8_t sub, std::string name,
                               DataType type, Access access, std::vector<std::uint8_t> initial,
                               bool pdo_mappable) {
  const std::size_t size = data_type_size(type);
  if (size != 0) initial.resize(size);
  OdEntry e;
  e.name = std::move(name);
  e.type = type;
  e.access = access;
  e.pdo_mappable = pdo_mappable;
  e.value = initial;
  e.default_value = std::move(initial);
  auto [it, inserted] = entries_.emplace(key(index, sub), std::move(e));
  if (!inserted) {
    throw std::logic_error("object dictionary entry " + hex_address(index, sub) + " defined twice");
  }
  return it->second;
}

OdEntry& ObjectDictionary::add_string(std::uint16_t index, std::uint8_t sub, std::string name,
                                      Access access, const std::string& text) {
  return add(index, sub, std::move(name), DataType::kVisibleString, access,
             std::vector<std::uint8_t>(text.begin(), text.end()));
}

std::uint32_t ObjectDictionary::locate(std::uint16_t index, std::uint8_t sub) const {
  if (entries_.contains(key(index, sub))) return sdo_abort::kNone;
  const auto it = entries_.lower_bound(key(index, 0));
  if (it != entries_.end() && (it->first >> 8) == index) return sdo_abort::kNoSubIndex;
  return sdo_abort::kNoObject;
}

const OdEntry* ObjectDictionary::find(std::uint16_t index, std::uint8_t sub) const {
  const auto it = entries_.find(key(index, sub));
  return it == entries_.end() ? nullptr : &it->second;
}

OdEntry* ObjectDictionary::find(std::uint16_t index, std::uint8_t sub) {
  const auto it = entries_.find(key(index, sub));
  return it == entries_.end() ? nullptr : &it->second;
}

std::uint32_t ObjectDictionary::read(std::uint16_t index, std::uint8_t sub,
                                     std::vector<std::uint8_t>& out) const {
  if (const std::uint32_t abort = locate(index, sub); abort != 0) return abort;
  const OdEntry& e = entries_.at(key(index, sub));
  if (e.access == Access::kWriteOnly) return sdo_abort::kWriteOnly;
  out = e.value;
  return sdo_abort::kNone;
}

std::uint32_t ObjectDictionary::check_writable(std::uint16_t index, std::uint8_t sub,
                                               std::optional<std::size_t> size) const {
  if (const std::uint32_t abort = locate(index, sub); abort != 0) return abort;
  const OdEntry& e = entries_.at(key(index, sub));
  if (e.access == Access::kReadOnly || e.access == Access::kConst) return sdo_abort::kReadOnly;
  const std::size_t fixed = data_type_size(e.type);
  if (size && fixed != 0 && *size != fixed) return sdo_abort::kLengthMismatch;
  return sdo_abort::kNone;
}

std::uint32_t ObjectDictionary::write(std::uint16_t index, std::uint8_t sub,
                                      std::span<const std::uint8_t> data) {
  if (const std::uint32_t abort = check_writable(index, sub, data.size()); abort != 0) {
    return abort;
  }
  OdEntry& e = entries_.at(key(index, sub));
  if (is_integer(e.type)) {
    const std::int64_t v = decode_integer(e.type, data);
    const bool unsigned64 = e.type == DataType::kUnsigned64;
    if (e.type == DataType::kBoolean && v > 1) return sdo_abort::kValueRange;
    if (!unsigned64 && ((e.min && v < *e.min) || (e.max && v > *e.max))) {
      return sdo_abort::kValueRange;
    }
  }
  if (e.on_write) {
    if (const std::uint32_t abort = e.on_write(data); abort != 0) return abort;
  }
  e.value.assign(data.begin(), data.end());
  if (e.after_write) e.after_write();
  return sdo_abort::kNone;
}

std::string ObjectDictionary::get_string(std::uint16_t index, std::uint8_t sub) const {
  const OdEntry& e = entry(index, sub);
  return {e.value.begin(), e.value.end()};
}

void ObjectDictionary::restore_defaults(std::uint16_t first, std::uint16_t last) {
  for (auto it = entries_.lower_bound(key(first, 0));
       it != entries_.end() && (it->first >> 8) <= last; ++it) {
    it->second.value = it->second.default_value;
  }
}

const OdEntry& ObjectDictionary::entry(std::uint16_t index, std::uint8_t sub) const {
  const auto it = entries_.find(key(index, sub));
  if (it == entries_.end()) {
    throw std::out_of_range("no object dictionary entry " + hex_address(index, sub));
  }
  return it->second;
}

OdEntry& ObjectDictionary::entry(std::uint16_t index, std::uint8_t sub) {
  const auto it = entries_.find(key(index, sub));
  if (it == entries_.end()) {
    throw std::out_of_range("no object dictionary entry " + hex_address(index, sub));
  }
  return it->second;
}

}  // namespace wavebench::simdevices
