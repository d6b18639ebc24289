#pragma once
// The parts of the EDS reader below the object model (eds.cpp): text, the CiA 306 line reader
// and value checks. Private to wavebench_canopen.

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace wavebench::canopen::eds_detail {

std::string lower(std::string_view s);
std::string_view trim(std::string_view s);
// `s` cut to at most `max` bytes at a UTF-8 character boundary, "..." added when cut: messages
// go into JSON, which must stay valid UTF-8.
std::string clip(std::string_view s, std::size_t max = 80);

bool valid_utf8(std::string_view s) noexcept;
// The file's text as UTF-8: a UTF-8 byte-order mark dropped; text that is not valid UTF-8 is
// read as Latin-1 (what Windows vendor tools write) and converted.
std::string to_utf8(std::string_view text);

// Warnings, bounded: past `max` only counted, and the last one says how many more there were.
// Each call returns the text it made, kept or not (Eds::problem quotes it).
class Warnings {
 public:
  Warnings(std::string source, std::size_t max) : source_(std::move(source)), max_(max) {}
  std::string add(std::string text);
  // "EDS <file>: [<section>] <key> = '<value>': expected <expected>"
  std::string value(std::string_view section, std::string_view key, std::string_view value,
                    std::string_view expected);
  // "EDS <file>: [<section>]: <what>"
  std::string section(std::string_view section, std::string_view what);
  // "EDS <file>: line <n>: <what>"
  std::string line(std::size_t line, std::string_view what);
  const std::string& source() const noexcept { return source_; }
  std::vector<std::string> take();

 private:
  std::string source_;
  std::size_t max_;
  std::size_t dropped_ = 0;
  std::vector<std::string> list_;
};

std::string value_message(std::string_view source, std::string_view section, std::string_view key,
                          std::string_view value, std::string_view expected);

struct IniKey {
  std::string name;   // as written
  std::string value;  // trimmed
  std::size_t line = 0;
};

struct IniSection {
  std::string name;  // as written, trimmed
  std::size_t line = 0;
  std::map<std::string, IniKey> keys;  // by lower-case name; the first of duplicates
  // The value of `key` (any case), or nullptr.
  const IniKey* get(std::string_view key) const;
};

struct IniFile {
  std::vector<IniSection> sections;            // in file order, the first of duplicates
  std::map<std::string, std::size_t> by_name;  // lower-case name -> position
  const IniSection* get(std::string_view name) const;
};

struct IniLimits {
  std::size_t max_line_bytes;
  std::size_t max_sections;
  std::size_t max_keys;
};

// Reads UTF-8 text (see to_utf8) as CiA 306 INI. A line that is not a section, a key, a comment
// (';' or '#') or blank, a key outside any section, and duplicates are warnings. Throws EdsError
// beyond `limits`.
IniFile read_ini(std::string_view text, const IniLimits& limits, Warnings& warnings);

// Whether `value` is a value of CiA 301 type `type` as CiA 306 writes it ($NODEID allowed in
// integers); nullopt when it is, else what was expected. An empty value is "not given".
std::optional<std::string> check_value(std::string_view value, std::uint16_t type);

}  // namespace wavebench::canopen::eds_detail
