// The object model of an EDS or DCF, built from its CiA 306 sections (eds_ini.cpp): which
// section is which object, what each key means, and what a vendor's mistake costs (a warning,
// or the one object it is in; never the file).
#include "wavebench/canopen/eds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <limits>

#include "eds_detail.hpp"

namespace wavebench::canopen {
namespace {

using eds_detail::IniFile;
using eds_detail::IniKey;
using eds_detail::IniSection;
using eds_detail::lower;
using eds_detail::Warnings;

std::uint32_t key_of(std::uint16_t index, std::uint8_t sub) {
  return static_cast<std::uint32_t>(index) << 8 | sub;
}

bool is_hex(std::string_view s) {
  return !s.empty() &&
         std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isxdigit(c) != 0; });
}

enum class SectionKind { kObject, kSub, kNames, kValues };

struct ObjectSectionName {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  SectionKind kind = SectionKind::kObject;
};

// "6041", "1018sub1", "1003Name", "1003Value" (any case); nullopt for any other section
// ([FileInfo], [DummyUsage], [Comments], a vendor tool's own).
std::optional<ObjectSectionName> object_section(std::string_view name) {
  if (name.size() < 4 || !is_hex(name.substr(0, 4))) return std::nullopt;
  ObjectSectionName out;
  out.index = static_cast<std::uint16_t>(std::stoul(std::string(name.substr(0, 4)), nullptr, 16));
  if (name.size() == 4) return out;
  const auto rest = lower(name.substr(4));
  if (rest == "name" || rest == "value") {
    out.kind = rest == "name" ? SectionKind::kNames : SectionKind::kValues;
    return out;
  }
  if (rest.size() < 4 || rest.compare(0, 3, "sub") != 0) return std::nullopt;
  const auto sub = std::string_view(rest).substr(3);
  if (!is_hex(sub) || sub.size() > 2) return std::nullopt;
  out.sub = static_cast<std::uint8_t>(std::stoul(std::string(sub), nullptr, 16));
  out.kind = SectionKind::kSub;
  return out;
}

std::string object_type_name(std::uint64_t type) {
  switch (type) {
    case kObjectDomain:
      return "DOMAIN";
    case kObjectDeftype:
      return "DEFTYPE";
    case kObjectDefstruct:
      return "DEFSTRUCT";
    case kObjectVar:
      return "VAR";
    case kObjectArray:
      return "ARRAY";
    case kObjectRecord:
      return "RECORD";
    default:
      return fmt::format("0x{:X}", type);
  }
}

}  // namespace

// Fills an Eds from the sections of one file; a friend of Eds.
class EdsBuilder {
 public:
  EdsBuilder(const IniFile& ini, Warnings& warnings, Eds& eds)
      : ini_(ini), warn_(warnings), eds_(eds) {}

  void build() {
    classify();
    if (parents_.empty() && subs_.empty())
      throw EdsError(
          fmt::format("EDS {}: no object sections ([1000], [1018sub1], ...): expected "
                      "a CiA 306 EDS or DCF",
                      eds_.source_));
    for (const auto& [index, section] : parents_) object(index, *section);
    for (const auto& [index, subs] : subs_) {
      if (parents_.contains(index)) continue;
      for (const auto& [sub, section] : subs) {
        eds_.problems_[key_of(index, sub)] = warn_.section(
            section->name, fmt::format("a sub-index of 0x{:04X}, which has no section [{:04X}]; "
                                       "left out",
                                       index, index));
      }
    }
    object_lists();
    device_info();
    commissioning();
  }

 private:
  // Where each object's sections are; duplicates of one sub-index warn (the first is used).
  void classify() {
    for (const auto& s : ini_.sections) {
      const auto id = object_section(s.name);
      if (!id) continue;
      switch (id->kind) {
        case SectionKind::kObject:
          parents_[id->index] = &s;  // the line reader made section names unique
          break;
        case SectionKind::kSub: {
          auto& subs = subs_[id->index];
          if (!subs.emplace(id->sub, &s).second)
            warn_.section(s.name, fmt::format("sub-index {} again (first as [{}]): ignored",
                                              id->sub, subs[id->sub]->name));
          break;
        }
        case SectionKind::kNames:
          names_[id->index] = &s;
          break;
        case SectionKind::kValues:
          values_[id->index] = &s;
          break;
      }
    }
  }

  // A key's value, nullptr when absent or empty (CiA 306: an empty value is not given).
  static const IniKey* given(const IniSection& s, std::string_view key) {
    const auto* k = s.get(key);
    return k && !k->value.empty() ? k : nullptr;
  }

  // An unsigned key in lo..hi; nullopt (with a warning) when malformed, nullopt when not given.
  std::optional<std::uint64_t> number(const IniSection& s, std::string_view key, std::uint64_t lo,
                                      std::uint64_t hi, std::string* warning = nullptr) {
    const auto* k = given(s, key);
    if (!k) return std::nullopt;
    std::string why;
    try {
      if (lower(k->value).find('$') != std::string::npos)
        throw std::invalid_argument("$NODEID has no place here");
      const auto v = parse_eds_unsigned(k->value);
      if (v >= lo && v <= hi) return v;
      why = "out of range";
    } catch (const std::invalid_argument& e) {
      why = e.what();
    }
    const auto text = warn_.value(s.name, k->name, k->value,
                                  fmt::format("an integer in {}..{} ({})", lo, hi, why));
    if (warning) *warning = text;
    return std::nullopt;
  }

  void object(std::uint16_t index, const IniSection& s) {
    std::uint64_t type = kObjectVar;  // CiA 306: VAR when ObjectType is not given
    if (given(s, "ObjectType")) {
      std::string why;
      const auto t = number(s, "ObjectType", 0, 0xFF, &why);
      if (!t) {
        eds_.index_problems_[index] = why;
        return;
      }
      type = *t;
    }
    const auto subs = subs_.find(index);
    switch (type) {
      case kObjectVar:
      case kObjectDomain:
      case kObjectDeftype:
        add(value_object(s, index, 0, static_cast<std::uint8_t>(type)));
        if (subs != subs_.end()) {
          for (const auto& [sub, section] : subs->second) {
            eds_.problems_[key_of(index, sub)] = warn_.section(
                section->name, fmt::format("a sub-index of [{}], which is a {} (no sub-indices); "
                                           "left out",
                                           s.name, object_type_name(type)));
          }
        }
        return;
      case kObjectArray:
      case kObjectRecord:
      case kObjectDefstruct:
        container(index, s, static_cast<std::uint8_t>(type));
        return;
      default:
        eds_.index_problems_[index] = warn_.value(
            s.name, s.get("ObjectType")->name, s.get("ObjectType")->value,
            "0x2 (DOMAIN), 0x5 (DEFTYPE), 0x6 (DEFSTRUCT), 0x7 (VAR), 0x8 (ARRAY) or 0x9 "
            "(RECORD); the object is left out");
        return;
    }
  }

  void add(std::optional<EdsObject> o) {
    if (o) eds_.objects_[key_of(o->index, o->sub)] = std::move(*o);
  }

  // An ARRAY, RECORD or DEFSTRUCT: its [XXXXsubN] sections, or CompactSubObj expanded.
  void container(std::uint16_t index, const IniSection& s, std::uint8_t type) {
    if (!given(s, "ParameterName")) warn_.value(s.name, "ParameterName", "", "a name");
    std::uint64_t compact = 0;
    if (given(s, "CompactSubObj")) {
      compact = number(s, "CompactSubObj", 0, 254).value_or(0);
      if (compact > 0 && type != kObjectArray) {
        warn_.value(s.name, s.get("CompactSubObj")->name, s.get("CompactSubObj")->value,
                    fmt::format("CompactSubObj only on an ARRAY (this is a {}); the [{:04X}subN] "
                                "sections are used",
                                object_type_name(type), index));
        compact = 0;
      }
    }
    const auto subs = subs_.find(index);
    const std::size_t sections = subs == subs_.end() ? 0 : subs->second.size();
    if (compact > 0) {
      expand(index, s, static_cast<std::uint8_t>(compact));
    } else if (!s.get("SubNumber")) {
      warn_.value(s.name, "SubNumber", "",
                  fmt::format("the number of sub-indices (missing; {} [{:04X}subN] sections "
                              "found)",
                              sections, index));
    } else if (const auto n = number(s, "SubNumber", 0, 255); n && *n != sections) {
      warn_.value(s.name, s.get("SubNumber")->name, s.get("SubNumber")->value,
                  fmt::format("the number of [{:04X}subN] sections, {}", index, sections));
    }
    if (subs == subs_.end()) return;
    // Written sub-sections; beside CompactSubObj they are the more specific and replace it.
    for (const auto& [sub, section] : subs->second) add(value_object(*section, index, sub, type));
  }

  // CiA 306 CompactSubObj=N: sub 0 holds N, subs 1..N share the section's type and access, with
  // names from [XXXXName] (else ParameterName and the sub-index) and DCF values from
  // [XXXXValue].
  void expand(std::uint16_t index, const IniSection& s, std::uint8_t count) {
    auto shared = value_object(s, index, 1, kObjectArray);
    if (!shared) {
      eds_.index_problems_[index] = eds_.problems_[key_of(index, 1)];
      eds_.problems_.erase(key_of(index, 1));
      return;
    }
    EdsObject sub0;
    sub0.index = index;
    sub0.sub = 0;
    sub0.name = "NrOfObjects";
    sub0.object_type = kObjectArray;
    sub0.data_type = datatype::kUnsigned8;
    sub0.access = EdsAccess::kRo;
    sub0.default_value = std::to_string(count);
    add(sub0);
    const auto names = entries(names_, index, count);
    const auto values = entries(values_, index, count);
    for (std::uint8_t sub = 1; sub <= count; ++sub) {
      EdsObject o = *shared;
      o.sub = sub;
      const auto name = names.find(sub);
      o.name = name != names.end() ? name->second.value : fmt::format("{}{}", shared->name, sub);
      o.parameter_value.reset();
      if (const auto v = values.find(sub); v != values.end()) {
        if (const auto bad = eds_detail::check_value(v->second.value, o.data_type)) {
          warn_.value(values_.at(index)->name, v->second.name, v->second.value, *bad);
        } else {
          o.parameter_value = v->second.value;
        }
      }
      add(std::move(o));
    }
  }

  // The entries 1..count of a [XXXXName] or [XXXXValue] section, by sub-index.
  std::map<std::uint8_t, IniKey> entries(const std::map<std::uint16_t, const IniSection*>& of,
                                         std::uint16_t index, std::uint8_t count) {
    std::map<std::uint8_t, IniKey> out;
    const auto it = of.find(index);
    if (it == of.end()) return out;
    const auto& s = *it->second;
    for (const auto& [lower_key, key] : s.keys) {
      if (lower_key == "nrofentries") continue;
      std::uint64_t sub = 0;
      try {
        sub = parse_eds_unsigned(lower_key);
      } catch (const std::invalid_argument&) {
        continue;  // a key of a vendor's tool
      }
      if (sub < 1 || sub > count) {
        warn_.value(s.name, key.name, key.value,
                    fmt::format("a sub-index in 1..{} (CompactSubObj of [{:04X}])", count, index));
        continue;
      }
      out.emplace(static_cast<std::uint8_t>(sub), key);
    }
    if (const auto n = number(s, "NrOfEntries", 0, 255); n && *n != out.size())
      warn_.value(s.name, s.get("NrOfEntries")->name, s.get("NrOfEntries")->value,
                  fmt::format("the number of entries, {}", out.size()));
    return out;
  }

  // A value of the object's type, or a warning and nothing.
  std::optional<std::string> value(const IniSection& s, std::string_view key,
                                   std::uint16_t data_type) {
    const auto* k = given(s, key);
    if (!k) return std::nullopt;
    if (const auto bad = eds_detail::check_value(k->value, data_type)) {
      warn_.value(s.name, k->name, k->value, *bad + "; ignored");
      return std::nullopt;
    }
    return k->value;
  }

  // One value object; nullopt, a warning and a problem when its DataType or AccessType is
  // missing or unreadable.
  std::optional<EdsObject> value_object(const IniSection& s, std::uint16_t index, std::uint8_t sub,
                                        std::uint8_t object_type) {
    EdsObject o;
    o.index = index;
    o.sub = sub;
    o.object_type = object_type;
    if (const auto* n = given(s, "ParameterName")) {
      o.name = n->value;
      if (o.name.size() > 241) warn_.value(s.name, n->name, n->value, "at most 241 characters");
    } else if (object_type != kObjectArray || sub == 0 || !s.get("CompactSubObj")) {
      warn_.value(s.name, "ParameterName", "", "a name (it is missing)");
    }
    // CiA 306: a DOMAIN's DataType and AccessType may be left out (DOMAIN, rw).
    const bool domain = object_type == kObjectDomain;
    auto left_out = [&](const IniKey* k, std::string_view key, std::string_view expected) {
      eds_.problems_[key_of(index, sub)] =
          warn_.value(s.name, k ? k->name : std::string(key), k ? k->value : "",
                      fmt::format("{}; the object is left out", expected));
      return std::nullopt;
    };
    if (const auto* t = given(s, "DataType")) {
      std::string why;
      try {
        const auto v = parse_eds_unsigned(t->value);
        if (v < 1 || v > 0xFFFF) throw std::invalid_argument("out of range");
        o.data_type = static_cast<std::uint16_t>(v);
      } catch (const std::invalid_argument& e) {
        return left_out(t, "DataType", fmt::format("a data type index in 1..65535 ({})", e.what()));
      }
    } else if (domain) {
      o.data_type = datatype::kDomain;
    } else {
      return left_out(s.get("DataType"), "DataType", "a data type index (it is missing)");
    }
    if (const auto* a = given(s, "AccessType")) {
      const auto access = lower(a->value);
      if (access == "ro") {
        o.access = EdsAccess::kRo;
      } else if (access == "wo") {
        o.access = EdsAccess::kWo;
      } else if (access == "rw") {
        o.access = EdsAccess::kRw;
      } else if (access == "rwr") {
        o.access = EdsAccess::kRwr;
      } else if (access == "rww") {
        o.access = EdsAccess::kRww;
      } else if (access == "const") {
        o.access = EdsAccess::kConst;
      } else {
        return left_out(a, "AccessType", "ro, wo, rw, rwr, rww or const");
      }
    } else if (domain) {
      o.access = EdsAccess::kRw;
    } else {
      return left_out(s.get("AccessType"), "AccessType",
                      "ro, wo, rw, rwr, rww or const (it is "
                      "missing)");
    }
    if (given(s, "PDOMapping")) o.pdo_mapping = number(s, "PDOMapping", 0, 1).value_or(0) == 1;
    o.default_value = value(s, "DefaultValue", o.data_type).value_or("");
    o.low_limit = value(s, "LowLimit", o.data_type);
    o.high_limit = value(s, "HighLimit", o.data_type);
    o.parameter_value = value(s, "ParameterValue", o.data_type);
    return o;
  }

  // [MandatoryObjects], [OptionalObjects], [ManufacturerObjects]: each entry has a section.
  void object_lists() {
    for (const char* list : {"MandatoryObjects", "OptionalObjects", "ManufacturerObjects"}) {
      const auto* s = ini_.get(list);
      if (!s) continue;
      std::size_t entries = 0;
      for (const auto& [lower_key, key] : s->keys) {
        if (lower_key == "supportedobjects") continue;
        try {
          (void)parse_eds_unsigned(lower_key);
        } catch (const std::invalid_argument&) {
          continue;  // a key of a vendor's tool
        }
        ++entries;
        std::uint64_t index = 0;
        try {
          index = parse_eds_unsigned(key.value);
          if (index > 0xFFFF) throw std::invalid_argument("out of range");
        } catch (const std::invalid_argument& e) {
          warn_.value(s->name, key.name, key.value,
                      fmt::format("an object index in 0..0xFFFF ({})", e.what()));
          continue;
        }
        if (!parents_.contains(static_cast<std::uint16_t>(index)))
          warn_.value(s->name, key.name, key.value,
                      fmt::format("an object with a section ([{:04X}] is missing)", index));
      }
      if (const auto n = number(*s, "SupportedObjects", 0, 0xFFFF); n && *n != entries)
        warn_.value(s->name, s->get("SupportedObjects")->name, s->get("SupportedObjects")->value,
                    fmt::format("the number of entries, {}", entries));
    }
  }

  void device_info() {
    const auto* s = ini_.get("DeviceInfo");
    if (!s) return;
    auto id = [&](const char* key, std::optional<std::uint32_t>& out) {
      if (const auto v = number(*s, key, 0, 0xFFFFFFFFULL)) out = static_cast<std::uint32_t>(*v);
    };
    id("VendorNumber", eds_.vendor_);
    id("ProductNumber", eds_.product_);
    id("RevisionNumber", eds_.revision_);
    if (const auto* k = given(*s, "VendorName")) eds_.vendor_name_ = k->value;
    if (const auto* k = given(*s, "ProductName")) eds_.product_name_ = k->value;
  }

  void commissioning() {
    const auto* s = ini_.get("DeviceComissioning");
    if (!s) return;
    auto& c = eds_.commissioning_;
    if (const auto v = number(*s, "NodeID", 1, 127)) c.node_id = static_cast<std::uint8_t>(*v);
    if (const auto v = number(*s, "Baudrate", 1, 1000))
      c.baudrate_kbit = static_cast<std::uint32_t>(*v);
    if (const auto* k = given(*s, "NodeName")) c.node_name = k->value;
  }

  const IniFile& ini_;
  Warnings& warn_;
  Eds& eds_;
  std::map<std::uint16_t, const IniSection*> parents_;
  std::map<std::uint16_t, std::map<std::uint8_t, const IniSection*>> subs_;
  std::map<std::uint16_t, const IniSection*> names_;
  std::map<std::uint16_t, const IniSection*> values_;
};

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
  if (const auto nul = text.find('\0'); nul != std::string::npos)
    throw EdsError(fmt::format("EDS {}: a NUL byte at offset {}: expected text", source, nul));
  Eds eds;
  eds.source_ = source;
  Warnings warnings(source, kMaxWarnings);
  const auto ini = eds_detail::read_ini(eds_detail::to_utf8(text),
                                        {kMaxLineBytes, kMaxSections, kMaxKeys}, warnings);
  EdsBuilder(ini, warnings, eds).build();
  eds.warnings_ = warnings.take();
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

std::optional<std::string> Eds::problem(std::uint16_t index, std::uint8_t sub) const {
  if (find(index, sub)) return std::nullopt;
  if (const auto it = problems_.find(key_of(index, sub)); it != problems_.end()) return it->second;
  if (const auto it = index_problems_.find(index); it != index_problems_.end()) return it->second;
  return std::nullopt;
}

std::optional<std::int64_t> Eds::default_integer(const EdsObject& object,
                                                 std::uint8_t node_id) const {
  if (object.default_value.empty() || !is_integer_type(object.data_type)) return std::nullopt;
  const auto bits = 8 * data_type_size(object.data_type);
  try {
    if (is_unsigned_type(object.data_type)) {
      const auto v = parse_eds_unsigned(object.default_value, node_id);
      if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
        return std::nullopt;
      return static_cast<std::int64_t>(v);
    }
    // A signed type written as its bit pattern (INTEGER16 0xFFFF) is sign-extended.
    const auto v = parse_eds_unsigned(object.default_value, node_id);
    if (bits == 64) return static_cast<std::int64_t>(v);
    const std::uint64_t sign = std::uint64_t{1} << (bits - 1);
    if (v >= sign && v < sign << 1)
      return static_cast<std::int64_t>(v) - static_cast<std::int64_t>(sign << 1);
    if (v >= sign << 1) return std::nullopt;
    return static_cast<std::int64_t>(v);
  } catch (const std::invalid_argument&) {
  }
  try {
    return parse_eds_integer(object.default_value, node_id);  // a negative one
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

std::optional<std::uint64_t> Eds::default_unsigned(const EdsObject& object,
                                                   std::uint8_t node_id) const {
  if (object.default_value.empty() || !is_unsigned_type(object.data_type)) return std::nullopt;
  try {
    return parse_eds_unsigned(object.default_value, node_id);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

}  // namespace wavebench::canopen
