#include <utility>

#include "wavebench/strict_yaml/strict_yaml.hpp"

namespace wavebench::strict_yaml {
namespace {

// A value quoted in a message stays readable: a 1 MiB line would bury the key.
constexpr std::size_t kMaxQuotedValue = 200;

std::string compose(const std::string& key, const std::string& value, const std::string& expected,
                    const std::string& source) {
  std::string shown = value;
  if (shown.size() > kMaxQuotedValue) shown = shown.substr(0, kMaxQuotedValue) + "...";
  std::string msg;
  if (!source.empty()) msg += source + ": ";
  msg += key.empty() ? std::string("(document)") : key;
  msg += ": got '" + shown + "', expected " + expected;
  return msg;
}

}  // namespace

RefusedConfig::RefusedConfig(std::string key, std::string value, std::string expected,
                             std::string source)
    : std::runtime_error(compose(key, value, expected, source)),
      key_(key.empty() ? "(document)" : std::move(key)),
      value_(std::move(value)),
      expected_(std::move(expected)),
      source_(std::move(source)) {}

RefusedConfig RefusedConfig::with_source(const std::string& source) const {
  return RefusedConfig(key_, value_, expected_, source);
}

}  // namespace wavebench::strict_yaml
