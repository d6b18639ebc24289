#include "wavebench/canopen/eds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/property_tree/ini_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <vector>

namespace wavebench::canopen {
namespace {

using boost::property_tree::ptree;

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// Keys of an INI section, lower-cased: CiA 306 keys are case-insensitive, property_tree's are not.
struct Section {
  std::string name;
  std::map<std::string, std::string> keys;
};

bool is_hex(std::string_view s) {
  return !s.empty() &&
         std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isxdigit(c) != 0; });
}

struct ObjectSectionName {
  std::uint16_t index = 0;
  std::optional<std::uint8_t> sub;
};

// "6041" or "1018sub1"; nullopt for any other section ([FileInfo], [6041Name], tool sections).
std::optional<ObjectSectionName> object_section(std::string_view name) {
  if (name.size() < 4 || !is_hex(name.substr(0, 4))) return std::nullopt;
  ObjectSectionName out;
  out.index = static_cast<std::uint16_t>(std::stoul(std::string(name.substr(0, 4)), nullptr, 16));
  if (name.size() == 4) return out;
  const auto rest = lower(name.substr(4));
  if (rest.size() < 4 || rest.compare(0, 3, "sub") != 0) return std::nullopt;
  const auto sub = std::string_view(rest).substr(3);
  if (!is_hex(sub) || sub.size() > 2) return std::nullopt;
  out.sub = static_cast<std::uint8_t>(std::stoul(std::string(sub), nullptr, 16));
  return out;
}

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const Section& s, const std::string& key, const std::string& value,
                         const std::string& expected) const {
    throw EdsError(fmt::format("EDS {}: [{}] {} = '{}': expected {}", source_, s.name, key,
                               value.size() > 80 ? value.substr(0, 80) + "..." : value, expected));
  }
  [[noreturn]] void fail_section(const std::string& section, const std::string& what) const {
    throw EdsError(fmt::format("EDS {}: [{}]: {}", source_, section, what));
  }

  const std::string* get(const Section& s, const char* key) const {
    const auto it = s.keys.find(lower(key));
    return it == s.keys.end() ? nullptr : &it->second;
  }
  const std::string& required(const Section& s, const char* key) const {
    const auto* v = get(s, key);
    if (!v) fail(s, key, "", "the key (it is missing)");
    return *v;
  }
  std::int64_t integer(const Section& s, const char* key, const std::string& value, std::int64_t lo,
                       std::int64_t hi) const {
    std::int64_t v = 0;
    try {
      v = parse_eds_integer(value);
    } catch (const std::invalid_argument& e) {
      fail(s, key, value, fmt::format("an integer in {}..{} ({})", lo, hi, e.what()));
    }
    if (v < lo || v > hi) fail(s, key, value, fmt::format("an integer in {}..{}", lo, hi));
    return v;
  }

  // A value of `type` with $NODEID allowed: checked here so that a bad one fails at load.
  void check_value(const Section& s, const char* key, const std::string& value,
                   std::uint16_t type) const {
    const auto text = trim(value);
    if (text.empty()) return;
    switch (type) {
      case datatype::kVisibleString:
      case datatype::kOctetString:
        return;
      case datatype::kReal32:
      case datatype::kReal64: {
        const std::string t(text);
        char* end = nullptr;
        const double d = std::strtod(t.c_str(), &end);
        if (end != t.c_str() + t.size() || !std::isfinite(d))
          fail(s, key, value, "a finite real number");
        return;
      }
      default:
        break;
    }
    try {
      parse_eds_integer(text, 1);
    } catch (const std::invalid_argument& e) {
      fail(s, key, value, std::string("an integer, optionally with $NODEID+ (") + e.what() + ")");
    }
  }

  EdsObject value_object(const Section& s, std::uint16_t index, std::uint8_t sub,
                         std::uint8_t object_type) const {
    EdsObject o;
    o.index = index;
    o.sub = sub;
    o.object_type = object_type;
    o.name = std::string(trim(required(s, "ParameterName")));
    if (o.name.empty() || o.name.size() > 241)
      fail(s, "ParameterName", o.name, "a name of 1 to 241 characters");
    o.data_type =
        static_cast<std::uint16_t>(integer(s, "DataType", required(s, "DataType"), 1, 0xFFFF));
    const auto& access = required(s, "AccessType");
    const auto a = lower(trim(access));
    if (a == "ro") {
      o.access = EdsAccess::kRo;
    } else if (a == "wo") {
      o.access = EdsAccess::kWo;
    } else if (a == "rw") {
      o.access = EdsAccess::kRw;
    } else if (a == "rwr") {
      o.access = EdsAccess::kRwr;
    } else if (a == "rww") {
      o.access = EdsAccess::kRww;
    } else if (a == "const") {
      o.access = EdsAccess::kConst;
    } else {
      fail(s, "AccessType", access, "ro, wo, rw, rwr, rww or const");
    }
    if (const auto* m = get(s, "PDOMapping")) o.pdo_mapping = integer(s, "PDOMapping", *m, 0, 1);
    if (const auto* d = get(s, "DefaultValue")) {
      check_value(s, "DefaultValue", *d, o.data_type);
      o.default_value = std::string(trim(*d));
    }
    if (const auto* l = get(s, "LowLimit")) {
      check_value(s, "LowLimit", *l, o.data_type);
      o.low_limit = std::string(trim(*l));
    }
    if (const auto* h = get(s, "HighLimit")) {
      check_value(s, "HighLimit", *h, o.data_type);
      o.high_limit = std::string(trim(*h));
    }
    return o;
  }

  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

std::uint32_t key_of(std::uint16_t index, std::uint8_t sub) {
  return static_cast<std::uint32_t>(index) << 8 | sub;
}

}  // namespace

std::string data_type_name(std::uint16_t type) {
  switch (type) {
    case datatype::kBoolean:
      return "BOOLEAN";
    case datatype::kInteger8:
      return "INTEGER8";
    case datatype::kInteger16:
      return "INTEGER16";
    case datatype::kInteger32:
      return "INTEGER32";
    case datatype::kUnsigned8:
      return "UNSIGNED8";
    case datatype::kUnsigned16:
      return "UNSIGNED16";
    case datatype::kUnsigned32:
      return "UNSIGNED32";
    case datatype::kReal32:
      return "REAL32";
    case datatype::kVisibleString:
      return "VISIBLE_STRING";
    case datatype::kOctetString:
      return "OCTET_STRING";
    case datatype::kReal64:
      return "REAL64";
    case datatype::kInteger64:
      return "INTEGER64";
    case datatype::kUnsigned64:
      return "UNSIGNED64";
    default:
      return fmt::format("type 0x{:04X}", type);
  }
}

std::size_t data_type_size(std::uint16_t type) noexcept {
  switch (type) {
    case datatype::kBoolean:
    case datatype::kInteger8:
    case datatype::kUnsigned8:
      return 1;
    case datatype::kInteger16:
    case datatype::kUnsigned16:
      return 2;
    case datatype::kInteger32:
    case datatype::kUnsigned32:
    case datatype::kReal32:
      return 4;
    case datatype::kReal64:
    case datatype::kInteger64:
    case datatype::kUnsigned64:
      return 8;
    default:
      return 0;
  }
}

std::string_view to_string(EdsAccess access) noexcept {
  switch (access) {
    case EdsAccess::kRo:
      return "ro";
    case EdsAccess::kWo:
      return "wo";
    case EdsAccess::kRw:
      return "rw";
    case EdsAccess::kRwr:
      return "rwr";
    case EdsAccess::kRww:
      return "rww";
    case EdsAccess::kConst:
      return "const";
  }
  return "?";
}

std::int64_t parse_eds_integer(std::string_view text, std::uint8_t node_id) {
  auto t = trim(text);
  if (t.empty()) throw std::invalid_argument("empty");
  if (t.size() > 40) throw std::invalid_argument("too long for a number");
  std::int64_t add = 0;
  const std::string l = lower(t);
  constexpr std::string_view kNodeId = "$nodeid";
  if (const auto at = l.find('$'); at != std::string::npos) {
    std::string_view rest = std::string_view(l);
    if (rest.substr(at, kNodeId.size()) != kNodeId)
      throw std::invalid_argument("'$' must begin $NODEID");
    if (l.find('$', at + 1) != std::string::npos)
      throw std::invalid_argument("$NODEID more than once");
    const auto before = trim(rest.substr(0, at));
    const auto after = trim(rest.substr(at + kNodeId.size()));
    if (before.empty() && after.empty()) return node_id;
    if (before.empty()) {
      if (after.front() != '+') throw std::invalid_argument("expected '+' after $NODEID");
      t = trim(t.substr(t.size() - after.size() + 1));
    } else {
      if (!after.empty() || before.back() != '+')
        throw std::invalid_argument("expected N+$NODEID or $NODEID+N");
      t = trim(t.substr(0, before.size() - 1));
    }
    if (t.empty()) throw std::invalid_argument("no number beside $NODEID");
    add = node_id;
  }
  bool negative = false;
  if (t.front() == '-' || t.front() == '+') {
    negative = t.front() == '-';
    t.remove_prefix(1);
  }
  int base = 10;
  if (t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) {
    base = 16;
    t.remove_prefix(2);
  } else if (t.size() > 1 && t[0] == '0') {
    base = 8;
    t.remove_prefix(1);
  }
  std::uint64_t magnitude = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), magnitude, base);
  if (ec == std::errc::result_out_of_range) throw std::invalid_argument("out of range");
  if (ec != std::errc() || end != t.data() + t.size() || t.empty())
    throw std::invalid_argument(base == 16  ? "not a hex number"
                                : base == 8 ? "not an octal number"
                                            : "not a decimal number");
  constexpr auto kMax = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  if (magnitude > kMax) throw std::invalid_argument("out of range");
  const auto v = static_cast<std::int64_t>(magnitude);
  return (negative ? -v : v) + add;
}

Eds Eds::load(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw EdsError(fmt::format("EDS {}: cannot read: {}", name, ec.message()));
  if (size > kMaxFileBytes)
    throw EdsError(
        fmt::format("EDS {}: {} bytes: expected at most {} bytes", name, size, kMaxFileBytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw EdsError(fmt::format("EDS {}: cannot open", name));
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (static_cast<std::size_t>(in.gcount()) != text.size())
    throw EdsError(fmt::format("EDS {}: short read", name));
  return parse(text, name);
}

Eds Eds::parse(const std::string& text, const std::string& source) {
  if (text.size() > kMaxFileBytes)
    throw EdsError(fmt::format("EDS {}: {} bytes: expected at most {} bytes", source, text.size(),
                               kMaxFileBytes));
  if (text.find('\0') != std::string::npos)
    throw EdsError(fmt::format("EDS {}: contains a NUL byte: expected INI text", source));
  ptree tree;
  try {
    std::istringstream in(text);
    boost::property_tree::ini_parser::read_ini(in, tree);
  } catch (const boost::property_tree::ini_parser_error& e) {
    throw EdsError(fmt::format("EDS {}: line {}: {}", source, e.line(), e.message()));
  }
  Reader reader(source);
  std::vector<Section> sections;
  std::map<std::string, std::size_t> by_name;  // lower-case name -> position
  for (const auto& [name, body] : tree) {
    if (body.empty() && !body.data().empty())
      throw EdsError(fmt::format("EDS {}: key '{}' outside any section", source, name));
    Section s{name, {}};
    for (const auto& [key, value] : body) {
      if (!s.keys.emplace(lower(key), value.data()).second)
        reader.fail(s, key, value.data(), "each key once (keys are case-insensitive)");
    }
    if (!by_name.emplace(lower(name), sections.size()).second)
      reader.fail_section(name, "appears twice (section names are case-insensitive)");
    sections.push_back(std::move(s));
  }

  Eds eds;
  eds.source_ = source;
  std::map<std::uint16_t, std::pair<const Section*, std::int64_t>> containers;  // sub counts
  for (const auto& s : sections) {
    const auto id = object_section(s.name);
    if (!id || id->sub) continue;
    const std::int64_t type =
        reader.get(s, "ObjectType")
            ? reader.integer(s, "ObjectType", *reader.get(s, "ObjectType"), 0, 0xFF)
            : kObjectVar;
    if (type == kObjectVar) {
      eds.objects_[key_of(id->index, 0)] =
          reader.value_object(s, id->index, 0, static_cast<std::uint8_t>(type));
    } else if (type == kObjectArray || type == kObjectRecord) {
      reader.required(s, "ParameterName");
      if (reader.get(s, "CompactSubObj"))
        reader.fail(s, "CompactSubObj", *reader.get(s, "CompactSubObj"),
                    "no CompactSubObj (write one [XXXXsubN] section per sub-index)");
      const auto n = reader.integer(s, "SubNumber", reader.required(s, "SubNumber"), 1, 255);
      containers[id->index] = {&s, n};
    } else {
      reader.fail(s, "ObjectType", *reader.get(s, "ObjectType"),
                  "0x7 (VAR), 0x8 (ARRAY) or 0x9 (RECORD)");
    }
  }
  std::map<std::uint16_t, std::int64_t> subs_seen;
  for (const auto& s : sections) {
    const auto id = object_section(s.name);
    if (!id || !id->sub) continue;
    const auto parent = containers.find(id->index);
    if (parent == containers.end())
      reader.fail_section(s.name, fmt::format("a sub-index of 0x{:04X}, which has no ARRAY or "
                                              "RECORD section [{:04X}]",
                                              id->index, id->index));
    const auto type = static_cast<std::uint8_t>(
        reader.integer(*parent->second.first, "ObjectType",
                       *reader.get(*parent->second.first, "ObjectType"), 0, 0xFF));
    eds.objects_[key_of(id->index, *id->sub)] = reader.value_object(s, id->index, *id->sub, type);
    ++subs_seen[id->index];
  }
  for (const auto& [index, parent] : containers) {
    const auto seen = subs_seen[index];
    if (seen != parent.second)
      reader.fail(*parent.first, "SubNumber", std::to_string(parent.second),
                  fmt::format("the number of [{:04X}subN] sections, {}", index, seen));
  }

  // The object lists must name objects that have sections.
  for (const char* list : {"MandatoryObjects", "OptionalObjects", "ManufacturerObjects"}) {
    const auto it = by_name.find(lower(list));
    if (it == by_name.end()) continue;
    const auto& s = sections[it->second];
    for (const auto& [key, value] : s.keys) {
      if (key == "supportedobjects") continue;
      const auto index = reader.integer(s, key.c_str(), value, 0, 0xFFFF);
      if (!eds.has_index(static_cast<std::uint16_t>(index)))
        reader.fail(s, key.c_str(), value,
                    fmt::format("an object with a section ([{:04X}] is missing)", index));
    }
  }
  if (const auto it = by_name.find("deviceinfo"); it != by_name.end()) {
    const auto& s = sections[it->second];
    auto number = [&](const char* key, std::optional<std::uint32_t>& out) {
      if (const auto* v = reader.get(s, key))
        out = static_cast<std::uint32_t>(reader.integer(s, key, *v, 0, 0xFFFFFFFFLL));
    };
    number("VendorNumber", eds.vendor_);
    number("ProductNumber", eds.product_);
    number("RevisionNumber", eds.revision_);
  }
  return eds;
}

const EdsObject* Eds::find(std::uint16_t index, std::uint8_t sub) const {
  const auto it = objects_.find(key_of(index, sub));
  return it == objects_.end() ? nullptr : &it->second;
}

bool Eds::has_index(std::uint16_t index) const {
  const auto it = objects_.lower_bound(key_of(index, 0));
  return it != objects_.end() && it->second.index == index;
}

std::optional<std::int64_t> Eds::default_integer(const EdsObject& object,
                                                 std::uint8_t node_id) const {
  if (object.default_value.empty()) return std::nullopt;
  if (object.data_type == datatype::kVisibleString || object.data_type == datatype::kOctetString ||
      object.data_type == datatype::kReal32 || object.data_type == datatype::kReal64)
    return std::nullopt;
  try {
    return parse_eds_integer(object.default_value, node_id);
  } catch (const std::invalid_argument& e) {
    throw EdsError(fmt::format(
        "EDS {}: [{:04X}{}] DefaultValue = '{}': expected an integer ({})", source_, object.index,
        object.object_type == kObjectVar ? "" : fmt::format("sub{:X}", object.sub),
        object.default_value, e.what()));
  }
}

}  // namespace wavebench::canopen
