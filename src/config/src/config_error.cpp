#include "wavebench/config/config_error.hpp"

#include <utility>

namespace wavebench::config {
namespace {

std::string compose(const std::string& key, const std::string& value, const std::string& expected,
                    const std::string& source) {
  std::string msg;
  if (!source.empty()) msg += source + ": ";
  msg += key.empty() ? std::string("(document)") : key;
  // A value quoted in a message stays readable: a whole list or a long line would bury the key.
  constexpr std::size_t kMaxQuoted = 200;
  msg += ": got '" + (value.size() > kMaxQuoted ? value.substr(0, kMaxQuoted) + "..." : value) +
         "', expected " + expected;
  return msg;
}

}  // namespace

ConfigError::ConfigError(std::string key, std::string value, std::string expected,
                         std::string source)
    : std::runtime_error(compose(key, value, expected, source)),
      key_(std::move(key)),
      value_(std::move(value)),
      expected_(std::move(expected)),
      source_(std::move(source)) {}

ConfigError ConfigError::with_source(const std::string& source) const {
  return ConfigError(key_, value_, expected_, source);
}

}  // namespace wavebench::config
