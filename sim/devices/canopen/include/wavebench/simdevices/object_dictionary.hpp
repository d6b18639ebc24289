#pragma once
// The object dictionary of a simulated CANopen node (CiA 301 §7.4): typed entries keyed by
// index and sub-index, holding their value as little-endian bytes as they travel on the bus.
// Bus access (SDO, RPDO) goes through read()/write(), which check existence, access, length and
// range and answer with an SDO abort code; the device model uses get()/set(), which do not.

#include <bit>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace wavebench::simdevices {

enum class DataType : std::uint16_t {  // CiA 301 data type indices
  kBoolean = 0x0001,
  kInteger8 = 0x0002,
  kInteger16 = 0x0003,
  kInteger32 = 0x0004,
  kUnsigned8 = 0x0005,
  kUnsigned16 = 0x0006,
  kUnsigned32 = 0x0007,
  kReal32 = 0x0008,
  kVisibleString = 0x0009,
  kReal64 = 0x0011,
  kInteger64 = 0x0015,
  kUnsigned64 = 0x001B,
};

enum class Access { kReadOnly, kWriteOnly, kReadWrite, kConst };

// Size in bytes of a fixed-size type; 0 for strings (their length is the value's).
std::size_t data_type_size(DataType type);

// Writes from the bus pass their checked bytes to this hook before they are stored; it returns
// an SDO abort code (0 accepts). Device models use it for side effects (controlword edges) and
// for rules that depend on other objects (PDO mapping only while the PDO is invalid).
using WriteHook = std::function<std::uint32_t(std::span<const std::uint8_t> data)>;

struct OdEntry {
  std::string name;
  DataType type = DataType::kUnsigned8;
  Access access = Access::kReadOnly;
  bool pdo_mappable = false;
  std::vector<std::uint8_t> value;
  std::vector<std::uint8_t> default_value;
  std::optional<std::int64_t> min;  // integer types: inclusive range for bus writes
  std::optional<std::int64_t> max;
  WriteHook on_write;
  std::function<void()> after_write;  // runs once a bus write is stored
};

template <typename T>
std::vector<std::uint8_t> to_le_bytes(T value) {
  static_assert(std::is_arithmetic_v<T>);
  std::vector<std::uint8_t> out(sizeof(T));
  if constexpr (std::is_floating_point_v<T>) {
    using Raw = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
    const Raw raw = std::bit_cast<Raw>(value);
    for (std::size_t i = 0; i < sizeof(T); ++i) out[i] = static_cast<std::uint8_t>(raw >> (8 * i));
  } else {
    using U = std::make_unsigned_t<T>;
    const U raw = static_cast<U>(value);
    for (std::size_t i = 0; i < sizeof(T); ++i) out[i] = static_cast<std::uint8_t>(raw >> (8 * i));
  }
  return out;
}

template <typename T>
T from_le_bytes(std::span<const std::uint8_t> bytes) {
  static_assert(std::is_arithmetic_v<T>);
  std::uint64_t raw = 0;
  for (std::size_t i = 0; i < sizeof(T) && i < bytes.size(); ++i) {
    raw |= static_cast<std::uint64_t>(bytes[i]) << (8 * i);
  }
  if constexpr (std::is_floating_point_v<T>) {
    using Raw = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
    return std::bit_cast<T>(static_cast<Raw>(raw));
  } else {
    return static_cast<T>(static_cast<std::make_unsigned_t<T>>(raw));
  }
}

class ObjectDictionary {
 public:
  // Adds an entry whose value and default are `initial`; throws if it exists already.
  OdEntry& add(std::uint16_t index, std::uint8_t sub, std::string name, DataType type,
               Access access, std::vector<std::uint8_t> initial, bool pdo_mappable = false);

  template <typename T>
  OdEntry& add_value(std::uint16_t index, std::uint8_t sub, std::string name, DataType type,
                     Access access, T initial, bool pdo_mappable = false) {
    return add(index, sub, std::move(name), type, access, to_le_bytes(initial), pdo_mappable);
  }
  OdEntry& add_string(std::uint16_t index, std::uint8_t sub, std::string name, Access access,
                      const std::string& text);

  // 0, sdo_abort::kNoObject (no such index) or sdo_abort::kNoSubIndex.
  std::uint32_t locate(std::uint16_t index, std::uint8_t sub) const;
  const OdEntry* find(std::uint16_t index, std::uint8_t sub) const;
  OdEntry* find(std::uint16_t index, std::uint8_t sub);

  // Bus access; the return value is an SDO abort code (0 = done).
  std::uint32_t read(std::uint16_t index, std::uint8_t sub, std::vector<std::uint8_t>& out) const;
  std::uint32_t write(std::uint16_t index, std::uint8_t sub, std::span<const std::uint8_t> data);
  // The checks of write() without storing or running the hook (for a segmented download's
  // initiate, which must refuse early).
  std::uint32_t check_writable(std::uint16_t index, std::uint8_t sub,
                               std::optional<std::size_t> size) const;

  // Device-side access: no access or range checks, no hooks.
  template <typename T>
  T get(std::uint16_t index, std::uint8_t sub) const {
    return from_le_bytes<T>(entry(index, sub).value);
  }
  template <typename T>
  void set(std::uint16_t index, std::uint8_t sub, T value) {
    OdEntry& e = entry(index, sub);
    auto bytes = to_le_bytes(value);
    bytes.resize(e.value.size());
    e.value = std::move(bytes);
  }
  // Changes value and default together (a device's factory configuration).
  template <typename T>
  void set_default(std::uint16_t index, std::uint8_t sub, T value) {
    set(index, sub, value);
    OdEntry& e = entry(index, sub);
    e.default_value = e.value;
  }
  std::string get_string(std::uint16_t index, std::uint8_t sub) const;

  // Puts every entry with first <= index <= last back to its default (NMT resets).
  void restore_defaults(std::uint16_t first, std::uint16_t last);

  std::size_t size() const { return entries_.size(); }
  // Every entry in index, sub-index order (an EDS is compared against them).
  template <typename F>
  void for_each(F&& visit) const {
    for (const auto& [k, e] : entries_)
      visit(static_cast<std::uint16_t>(k >> 8), static_cast<std::uint8_t>(k & 0xFFU), e);
  }

 private:
  static std::uint32_t key(std::uint16_t index, std::uint8_t sub) {
    return (static_cast<std::uint32_t>(index) << 8) | sub;
  }
  const OdEntry& entry(std::uint16_t index, std::uint8_t sub) const;
  OdEntry& entry(std::uint16_t index, std::uint8_t sub);

  std::map<std::uint32_t, OdEntry> entries_;
};

}  // namespace wavebench::simdevices
