#pragma once
// A CiA 306 electronic data sheet (EDS, or a DCF, which has the same sections): the objects a
// device has, each with its name, object type, data type, access, PDO mapping, default value
// and limits. Read with boost::property_tree's INI parser; what CiA 306 adds on top of INI
// (hex numbers, $NODEID in values, [XXXXsubN] sections) is handled here.
//
// Hostile input: the file is bounded in size, and every refusal (EdsError) names the file, the
// section, the key and the value and says what was expected.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace wavebench::canopen {

// CiA 301 data type indices (the EDS DataType key).
namespace datatype {
inline constexpr std::uint16_t kBoolean = 0x0001;
inline constexpr std::uint16_t kInteger8 = 0x0002;
inline constexpr std::uint16_t kInteger16 = 0x0003;
inline constexpr std::uint16_t kInteger32 = 0x0004;
inline constexpr std::uint16_t kUnsigned8 = 0x0005;
inline constexpr std::uint16_t kUnsigned16 = 0x0006;
inline constexpr std::uint16_t kUnsigned32 = 0x0007;
inline constexpr std::uint16_t kReal32 = 0x0008;
inline constexpr std::uint16_t kVisibleString = 0x0009;
inline constexpr std::uint16_t kOctetString = 0x000A;
inline constexpr std::uint16_t kReal64 = 0x0011;
inline constexpr std::uint16_t kInteger64 = 0x0015;
inline constexpr std::uint16_t kUnsigned64 = 0x001B;
}  // namespace datatype

// "UNSIGNED16", or "type 0x1234" for one without a name here.
std::string data_type_name(std::uint16_t type);
// Bytes of a fixed-size type; 0 for strings and unknown types.
std::size_t data_type_size(std::uint16_t type) noexcept;

enum class EdsAccess { kRo, kWo, kRw, kRwr, kRww, kConst };
std::string_view to_string(EdsAccess access) noexcept;
inline bool readable(EdsAccess a) noexcept {
  return a != EdsAccess::kWo;
}
inline bool writable(EdsAccess a) noexcept {
  return a == EdsAccess::kWo || a == EdsAccess::kRw || a == EdsAccess::kRwr || a == EdsAccess::kRww;
}

inline constexpr std::uint8_t kObjectVar = 0x07;
inline constexpr std::uint8_t kObjectArray = 0x08;
inline constexpr std::uint8_t kObjectRecord = 0x09;

// One value object: a VAR at sub-index 0, or one sub-index of an ARRAY or RECORD.
struct EdsObject {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::string name;
  std::uint8_t object_type = kObjectVar;  // of the section it comes from
  std::uint16_t data_type = 0;
  EdsAccess access = EdsAccess::kRo;
  bool pdo_mapping = false;
  std::string default_value;  // as written; see Eds::default_integer
  std::optional<std::string> low_limit;
  std::optional<std::string> high_limit;
};

class EdsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Eds {
 public:
  static constexpr std::size_t kMaxFileBytes = 4 * 1024 * 1024;

  // Throws EdsError (file unreadable, too large, not INI, or a bad section, key or value).
  static Eds load(const std::filesystem::path& path);
  static Eds parse(const std::string& text, const std::string& source = "<eds>");

  const std::string& source() const noexcept { return source_; }
  const EdsObject* find(std::uint16_t index, std::uint8_t sub) const;
  bool has_index(std::uint16_t index) const;
  const std::map<std::uint32_t, EdsObject>& objects() const noexcept { return objects_; }
  // [DeviceInfo] VendorNumber, ProductNumber, RevisionNumber where given.
  std::optional<std::uint32_t> vendor_number() const noexcept { return vendor_; }
  std::optional<std::uint32_t> product_number() const noexcept { return product_; }
  std::optional<std::uint32_t> revision_number() const noexcept { return revision_; }

  // The object's DefaultValue as an integer, $NODEID replaced by `node_id`; nullopt when the
  // object has none or it is not an integer expression. Throws EdsError for a malformed one.
  std::optional<std::int64_t> default_integer(const EdsObject& object,
                                              std::uint8_t node_id = 0) const;

 private:
  std::string source_;
  std::map<std::uint32_t, EdsObject> objects_;  // key index << 8 | sub
  std::optional<std::uint32_t> vendor_;
  std::optional<std::uint32_t> product_;
  std::optional<std::uint32_t> revision_;
};

// A CiA 306 integer value: decimal, 0x hex or 0 octal, optionally "$NODEID+" before or "+$NODEID"
// after it (case-insensitive). `node_id` replaces $NODEID. Throws std::invalid_argument saying
// what is wrong with the text.
std::int64_t parse_eds_integer(std::string_view text, std::uint8_t node_id = 0);

}  // namespace wavebench::canopen
