#pragma once
// A request body as JSON, bounded before it is built: nesting deeper than kMaxRequestDepth or
// more than kMaxRequestValues values is refused while parsing, so a hostile body can neither
// exhaust the stack (serialising deep JSON recurses) nor memory.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace wavebench::daemon {

inline constexpr int kMaxRequestDepth = 16;
inline constexpr std::size_t kMaxRequestValues = 10000;

struct RequestJson {
  nlohmann::json value;  // discarded when error is set
  std::string error;     // why the body was refused, for a 400 answer
};

RequestJson parse_request_json(std::string_view body);

}  // namespace wavebench::daemon
