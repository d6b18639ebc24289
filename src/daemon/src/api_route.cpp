#include "wavebench/daemon/api_route.hpp"

namespace wavebench::daemon {

namespace {

std::vector<std::string_view> pattern_segments(std::string_view pattern) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (start < pattern.size()) {
    const auto end = pattern.find('/', start);
    const auto stop = end == std::string_view::npos ? pattern.size() : end;
    if (stop > start) out.push_back(pattern.substr(start, stop - start));
    start = stop + 1;
  }
  return out;
}

bool is_parameter(std::string_view segment) {
  return segment.size() >= 2 && segment.front() == '{' && segment.back() == '}';
}

}  // namespace

bool route_matches(std::string_view pattern, const std::vector<std::string>& segments) {
  const auto parts = pattern_segments(pattern);
  if (parts.size() != segments.size()) return false;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (!is_parameter(parts[i]) && parts[i] != segments[i]) return false;
  }
  return true;
}

std::vector<std::size_t> run_id_segments(std::string_view pattern) {
  std::vector<std::size_t> out;
  const auto parts = pattern_segments(pattern);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (parts[i] == "{run}") out.push_back(i);
  }
  return out;
}

std::string method_list_text(const std::vector<std::string_view>& methods) {
  std::string text;
  for (std::size_t i = 0; i < methods.size(); ++i) {
    if (i > 0) text += i + 1 == methods.size() ? " or " : ", ";
    text += methods[i];
  }
  return text;
}

}  // namespace wavebench::daemon
