#include "wavebench/daemon/request_json.hpp"

#include <stdexcept>

namespace wavebench::daemon {

namespace {

struct TooLarge : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace

RequestJson parse_request_json(std::string_view body) {
  RequestJson r;
  std::size_t values = 0;
  // nlohmann's parser is iterative; the callback sees each value's depth before the value is
  // kept, so the bound holds before anything deep exists.
  using Event = nlohmann::json::parse_event_t;
  const nlohmann::json::parser_callback_t bound = [&](int depth, Event event, nlohmann::json&) {
    if (depth > kMaxRequestDepth) {
      throw TooLarge("nested deeper than " + std::to_string(kMaxRequestDepth) + " levels");
    }
    const bool starts_value =
        event == Event::value || event == Event::object_start || event == Event::array_start;
    if (starts_value && ++values > kMaxRequestValues) {
      throw TooLarge("more than " + std::to_string(kMaxRequestValues) + " values");
    }
    return true;
  };
  try {
    r.value = nlohmann::json::parse(body.begin(), body.end(), bound, true);
  } catch (const TooLarge& e) {
    r.value = nlohmann::json(nlohmann::json::value_t::discarded);
    r.error = std::string("body: ") + e.what() + "; expected a small JSON object";
  } catch (const nlohmann::json::exception& e) {
    r.value = nlohmann::json(nlohmann::json::value_t::discarded);
    r.error = std::string("body: not JSON (") + e.what() + ")";
  }
  return r;
}

}  // namespace wavebench::daemon
