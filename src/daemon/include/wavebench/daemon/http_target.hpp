#pragma once
// A request target split into its path segments and its decoded query parameters.

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace wavebench::daemon {

struct HttpTarget {
  std::string path;                   // decoded, without the query
  std::vector<std::string> segments;  // path split on '/', empty ones dropped
  std::map<std::string, std::string> query;
};

// Throws std::invalid_argument on a malformed %-escape.
HttpTarget parse_http_target(std::string_view target);
std::string url_decode(std::string_view text);
std::string url_encode(std::string_view text);

}  // namespace wavebench::daemon
