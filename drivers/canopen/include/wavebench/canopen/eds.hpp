#pragma once
// A CiA 306 electronic data sheet (EDS, or a DCF, which has the same sections plus configured
// values): the objects a device has, each with its name, object type, data type, access, PDO
// mapping, default value and limits. Read with a CiA 306 line reader of our own (eds_ini.cpp):
// CiA 306 INI is not the INI of general parsers (case-insensitive keys and sections, ';'
// comments, duplicates tolerated, Latin-1 text from vendor tools).
//
// What vendors write is read; what they get wrong in one object costs that object only. An
// inconsistency (a SubNumber that disagrees, an object list naming a missing section, a
// malformed value, an unknown ObjectType, a duplicate) is a warning (Eds::warnings()); an object
// whose DataType or AccessType is unreadable is left out of objects() and Eds::problem() says
// why. Only a file that means nothing as a whole is refused (EdsError): unreadable, too large,
// not text, beyond the bounds below, or without a single object section.
//
// Hostile input: the file, its lines, sections, keys and warnings are bounded, and every refusal
// and warning names the file, the section, the key and the value and says what was expected.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

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
inline constexpr std::uint16_t kUnicodeString = 0x000B;
inline constexpr std::uint16_t kTimeOfDay = 0x000C;
inline constexpr std::uint16_t kTimeDifference = 0x000D;
inline constexpr std::uint16_t kDomain = 0x000F;
inline constexpr std::uint16_t kInteger24 = 0x0010;
inline constexpr std::uint16_t kReal64 = 0x0011;
inline constexpr std::uint16_t kInteger40 = 0x0012;
inline constexpr std::uint16_t kInteger48 = 0x0013;
inline constexpr std::uint16_t kInteger56 = 0x0014;
inline constexpr std::uint16_t kInteger64 = 0x0015;
inline constexpr std::uint16_t kUnsigned24 = 0x0016;
inline constexpr std::uint16_t kUnsigned40 = 0x0018;
inline constexpr std::uint16_t kUnsigned48 = 0x0019;
inline constexpr std::uint16_t kUnsigned56 = 0x001A;
inline constexpr std::uint16_t kUnsigned64 = 0x001B;
}  // namespace datatype

// "UNSIGNED16", or "type 0x1234" for one without a name here.
std::string data_type_name(std::uint16_t type);
// Bytes of a fixed-size type; 0 for strings, DOMAIN and unknown types.
std::size_t data_type_size(std::uint16_t type) noexcept;
// BOOLEAN, INTEGERn and UNSIGNEDn: the types whose values are integers.
bool is_integer_type(std::uint16_t type) noexcept;
bool is_unsigned_type(std::uint16_t type) noexcept;  // BOOLEAN and UNSIGNEDn

enum class EdsAccess { kRo, kWo, kRw, kRwr, kRww, kConst };
std::string_view to_string(EdsAccess access) noexcept;
inline bool readable(EdsAccess a) noexcept {
  return a != EdsAccess::kWo;
}
inline bool writable(EdsAccess a) noexcept {
  return a == EdsAccess::kWo || a == EdsAccess::kRw || a == EdsAccess::kRwr || a == EdsAccess::kRww;
}

// CiA 301 object codes (the EDS ObjectType key).
inline constexpr std::uint8_t kObjectDomain = 0x02;
inline constexpr std::uint8_t kObjectDeftype = 0x05;
inline constexpr std::uint8_t kObjectDefstruct = 0x06;
inline constexpr std::uint8_t kObjectVar = 0x07;
inline constexpr std::uint8_t kObjectArray = 0x08;
inline constexpr std::uint8_t kObjectRecord = 0x09;

// One value object: a VAR, DOMAIN or DEFTYPE at sub-index 0, or one sub-index of an ARRAY,
// RECORD or DEFSTRUCT (written as [XXXXsubN] or expanded from CompactSubObj).
struct EdsObject {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::string name;                       // UTF-8 (a Latin-1 file is converted)
  std::uint8_t object_type = kObjectVar;  // of the section it comes from
  std::uint16_t data_type = 0;
  EdsAccess access = EdsAccess::kRo;
  bool pdo_mapping = false;
  std::string default_value;  // as written, empty when not given; see Eds::default_integer
  std::optional<std::string> low_limit;
  std::optional<std::string> high_limit;
  // A DCF's configured value (ParameterValue, or the [XXXXValue] entry of a compact array).
  std::optional<std::string> parameter_value;
};

// A DCF's [DeviceComissioning] (CiA 306 spells it with one m), where given.
struct EdsCommissioning {
  std::optional<std::uint8_t> node_id;         // NodeID, 1..127
  std::optional<std::uint32_t> baudrate_kbit;  // Baudrate, kbit/s
  std::string node_name;                       // NodeName; empty when not given
};

class EdsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Eds {
 public:
  static constexpr std::size_t kMaxFileBytes = 4 * 1024 * 1024;
  // Far above what any device needs (the largest vendor files have a few thousand sections of
  // about ten keys), low enough that a hostile file cannot exhaust memory.
  static constexpr std::size_t kMaxLineBytes = 64 * 1024;
  static constexpr std::size_t kMaxSections = 65536;
  static constexpr std::size_t kMaxKeys = 262144;
  static constexpr std::size_t kMaxWarnings = 1000;

  // Throws EdsError only for a file that means nothing as a whole (see the top of this file).
  static Eds load(const std::filesystem::path& path);
  static Eds parse(const std::string& text, const std::string& source = "<eds>");

  const std::string& source() const noexcept { return source_; }
  const EdsObject* find(std::uint16_t index, std::uint8_t sub) const;
  bool has_index(std::uint16_t index) const;
  const std::map<std::uint32_t, EdsObject>& objects() const noexcept { return objects_; }

  // What was wrong but did not refuse the file, in file order, at most kMaxWarnings (the last
  // then says how many more there were). Each names the file, section, key, value and expectation.
  const std::vector<std::string>& warnings() const noexcept { return warnings_; }
  // Why an object the file has a section for is not in objects() (its DataType or AccessType
  // is unreadable, its ObjectType unknown, its parent missing); nullopt when there is no reason.
  std::optional<std::string> problem(std::uint16_t index, std::uint8_t sub) const;

  // [DeviceInfo] VendorNumber, ProductNumber, RevisionNumber where given (an empty value or a
  // malformed one, which warns, is not given).
  std::optional<std::uint32_t> vendor_number() const noexcept { return vendor_; }
  std::optional<std::uint32_t> product_number() const noexcept { return product_; }
  std::optional<std::uint32_t> revision_number() const noexcept { return revision_; }
  // [DeviceInfo] VendorName, ProductName; empty when not given.
  const std::string& vendor_name() const noexcept { return vendor_name_; }
  const std::string& product_name() const noexcept { return product_name_; }
  const EdsCommissioning& commissioning() const noexcept { return commissioning_; }

  // The object's DefaultValue as an integer, $NODEID replaced by `node_id`; nullopt when the
  // object has none, is not of an integer type, or the value does not fit an int64 (an
  // UNSIGNED64 above INT64_MAX: see default_unsigned). Never throws: a malformed value was
  // dropped with a warning when the file was read.
  std::optional<std::int64_t> default_integer(const EdsObject& object,
                                              std::uint8_t node_id = 0) const;
  // The same for BOOLEAN and UNSIGNEDn objects over the whole UNSIGNED64 range.
  std::optional<std::uint64_t> default_unsigned(const EdsObject& object,
                                                std::uint8_t node_id = 0) const;

 private:
  std::string source_;
  std::map<std::uint32_t, EdsObject> objects_;  // key index << 8 | sub
  std::vector<std::string> warnings_;
  std::map<std::uint32_t, std::string> problems_;        // key index << 8 | sub
  std::map<std::uint16_t, std::string> index_problems_;  // a whole object left out
  std::optional<std::uint32_t> vendor_;
  std::optional<std::uint32_t> product_;
  std::optional<std::uint32_t> revision_;
  std::string vendor_name_;
  std::string product_name_;
  EdsCommissioning commissioning_;

  friend class EdsBuilder;
};

// A CiA 306 integer value: decimal, 0x hex or 0 octal, optionally negative, optionally
// "$NODEID+" before or "+$NODEID" after it (case-insensitive). `node_id` replaces $NODEID.
// Throws std::invalid_argument saying what is wrong with the text (or that it is out of range).
std::int64_t parse_eds_integer(std::string_view text, std::uint8_t node_id = 0);
// The same for an unsigned value, 0..UINT64_MAX; a negative one is refused.
std::uint64_t parse_eds_unsigned(std::string_view text, std::uint8_t node_id = 0);

}  // namespace wavebench::canopen
