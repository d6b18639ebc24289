#pragma once
// The checks every config file passes before any loader reads a key: a regular file of at most
// kMaxConfigBytes, UTF-8 text without control characters, a document that is not empty, nested
// at most kMaxDepth deep, with at most kMaxNodeVisits nodes (aliases counted each time they are
// used, so an alias bomb is refused before a loader expands it) and no key twice in a mapping.

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace wavebench::strict_yaml {

inline constexpr std::size_t kMaxConfigBytes = 1 << 20;  // the largest shipped config is ~5 KiB
inline constexpr int kMaxDepth = 32;                     // shipped configs nest 4 deep
inline constexpr std::size_t kMaxNodeVisits = 200000;

// A config that cannot be used, refused by the file checks, the parser or a YamlSection (the
// one error type of every config loader; config::ConfigError is this type). what() is
// "source: key: got 'value', expected ...", so a user can fix the file without the code.
class RefusedConfig : public std::runtime_error {
 public:
  RefusedConfig(std::string key, std::string value, std::string expected, std::string source = {});

  const std::string& key() const noexcept { return key_; }  // "(document)" when no key applies
  const std::string& value() const noexcept { return value_; }
  const std::string& expected() const noexcept { return expected_; }
  const std::string& source() const noexcept { return source_; }

  // The same refusal attributed to a file.
  RefusedConfig with_source(const std::string& source) const;

 private:
  std::string key_, value_, expected_, source_;
};

// The text of a config file. Refuses a folder, a device, a FIFO or anything else that is not a
// regular file, a file larger than kMaxConfigBytes and an unreadable file.
std::string read_config_file(const std::filesystem::path& path);

// Parses `text` (named `source` in errors) after checking size and UTF-8, then refuses an empty
// or null document, deep nesting, too many nodes, non-text keys and duplicate keys at any depth.
YAML::Node parse_strict_yaml(const std::string& text, const std::string& source);

// The first place `text` is not UTF-8 (or holds a control character other than tab, LF, CR),
// or text.size() when it is clean. A leading byte-order mark is allowed.
std::size_t first_non_utf8_byte(const std::string& text);

}  // namespace wavebench::strict_yaml
