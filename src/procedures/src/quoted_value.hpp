#pragma once
// A value as quoted in a refusal, cut short: a hostile request may carry megabytes, and the
// message goes to a log, a terminal and an HTTP body.

#include <nlohmann/json.hpp>
#include <string>

namespace wavebench::procedures {

inline std::string quoted_value(std::string text) {
  constexpr std::size_t kMaxQuoted = 120;
  if (text.size() > kMaxQuoted) {
    text = text.substr(0, kMaxQuoted) + "... (" + std::to_string(text.size()) + " characters)";
  }
  return text;
}

inline std::string quoted_value(const nlohmann::json& value) {
  return quoted_value(value.is_string() ? value.get<std::string>() : value.dump());
}

}  // namespace wavebench::procedures
