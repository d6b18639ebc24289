#pragma once
// A config that cannot be used. The message names the key path, the offending value and what
// was expected, so a user can fix the file without reading the code.

#include <stdexcept>
#include <string>

namespace wavebench::config {

class ConfigError : public std::runtime_error {
 public:
  ConfigError(std::string key, std::string value, std::string expected, std::string source = {});

  const std::string& key() const noexcept { return key_; }      // e.g. "stiffness.k0"
  const std::string& value() const noexcept { return value_; }  // as written in the file
  const std::string& expected() const noexcept { return expected_; }
  const std::string& source() const noexcept { return source_; }  // file name, if known

  // The same error attributed to a file.
  ConfigError with_source(const std::string& source) const;

 private:
  std::string key_, value_, expected_, source_;
};

}  // namespace wavebench::config
