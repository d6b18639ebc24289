#include "wavebench/daemon/manual_api.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "wavebench/daemon/printable_text.hpp"
#include "wavebench/daemon/request_json.hpp"

namespace wavebench::daemon {

namespace {

struct BadBody {
  std::string detail;
};

// The body's number at `key`; `fallback` when absent and allowed.
double number_at(const nlohmann::json& body, const char* key, const char* expected,
                 std::optional<double> fallback = std::nullopt) {
  const auto it = body.find(key);
  if (it == body.end() && fallback) return *fallback;
  if (it == body.end() || !it->is_number())
    throw BadBody{std::string(key) + ": got " + (it == body.end() ? "nothing" : it->dump()) +
                  ", expected " + expected};
  return it->get<double>();
}

ApiResponse answer(BenchThread& bench, const std::optional<ManualRefusal>& refused) {
  if (refused) {
    return api_error(refused->status, refused->status == 400 ? "bad request" : "conflict",
                     refused->detail);
  }
  return {200, {{"manual", manual_json(bench.status().manual)}}};
}

struct Action {
  std::set<std::string> keys;
  std::function<ApiResponse(BenchThread&, const nlohmann::json&)> act;
};

const std::map<std::string, Action>& actions() {
  static const std::map<std::string, Action> table = {
      {"jog",
       {{"speed_rpm"},
        [](BenchThread& bench, const nlohmann::json& body) {
          const double rpm = number_at(body, "speed_rpm", "a signed speed in rpm at the input");
          return answer(bench, bench.manual([&](ManualSession& m) { return m.jog(rpm); }));
        }}},
      {"stop",
       {{},
        [](BenchThread& bench, const nlohmann::json&) {
          bench.manual_stop("manual stop from the console");
          return answer(bench, std::nullopt);
        }}},
      {"goto",
       {{"angle_deg", "speed_rpm"},
        [](BenchThread& bench, const nlohmann::json& body) {
          const double angle = number_at(body, "angle_deg", "an output angle in degrees");
          const double max = bench.status().manual.max_speed_rpm;
          const double rpm =
              number_at(body, "speed_rpm", "a speed in rpm at the input", std::optional(max));
          return answer(bench, bench.manual([&](ManualSession& m) { return m.go_to(angle, rpm); }));
        }}},
      {"brake",
       {{"torque_nm"},
        [](BenchThread& bench, const nlohmann::json& body) {
          const double torque = number_at(body, "torque_nm", "a brake torque in N·m");
          return answer(bench, bench.manual([&](ManualSession& m) { return m.brake(torque); }));
        }}},
      {"servo",
       {{"on"},
        [](BenchThread& bench, const nlohmann::json& body) {
          const auto on = body.find("on");
          if (on == body.end() || !on->is_boolean())
            throw BadBody{"on: got " + (on == body.end() ? std::string("nothing") : on->dump()) +
                          ", expected true or false"};
          if (!on->get<bool>()) {
            // Switching off is never refused: it only makes the bench safer (in a fault or a
            // run the panel holds nothing anyway).
            bench.manual_stop("servo switched off");
            (void)bench.manual([](ManualSession& m) {
              m.servo(false);
              return std::optional<ManualRefusal>();
            });
            return answer(bench, std::nullopt);
          }
          return answer(bench, bench.manual([](ManualSession& m) {
            m.servo(true);
            return std::optional<ManualRefusal>();
          }));
        }}},
      {"alive",
       {{},
        [](BenchThread& bench, const nlohmann::json&) {
          return answer(bench, bench.manual([](ManualSession& m) {
            m.keep_alive();
            return std::optional<ManualRefusal>();
          }));
        }}},
  };
  return table;
}

std::string action_names() {
  std::string names;
  for (const auto& [name, action] : actions()) names += (names.empty() ? "" : ", ") + name;
  return names;
}

}  // namespace

nlohmann::json manual_json(const ManualState& s) {
  return {
      {"servo_on", s.servo_on},
      {"jog_rpm", s.jog_rpm},
      {"goto_deg", s.goto_deg ? nlohmann::json(*s.goto_deg) : nlohmann::json(nullptr)},
      {"brake_nm", s.brake_nm},
      {"last_stop", s.last_stop.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.last_stop)},
      {"max_speed_rpm", s.max_speed_rpm},
      {"max_brake_torque_nm", s.max_brake_torque_nm},
      {"jog_timeout_s", s.jog_timeout_s},
      {"stop_within_s", s.stop_within_s},
      {"hold_timeout_s", s.hold_timeout_s}};
}

ApiResponse manual_request(BenchThread& bench, const std::string& action, const std::string& body) {
  const auto it = actions().find(action);
  if (it == actions().end())
    return api_error(404, "not found",
                     "/api/manual/" + action + ": no such action; expected " + action_names());
  nlohmann::json parsed = nlohmann::json::object();
  if (!body.empty()) {
    auto json = parse_request_json(body);
    if (!json.error.empty()) return api_error(400, "bad request", json.error);
    if (!json.value.is_object())
      return api_error(400, "bad request",
                       "body: got '" + printable_text(body) + "', expected a JSON object");
    parsed = std::move(json.value);
  }
  for (const auto& [key, value] : parsed.items()) {
    if (!it->second.keys.contains(key)) {
      std::string expected;
      for (const auto& k : it->second.keys) expected += (expected.empty() ? "" : ", ") + k;
      return api_error(400, "bad request",
                       key + ": unknown key for " + action + "; expected " +
                           (expected.empty() ? std::string("none") : expected));
    }
  }
  try {
    return it->second.act(bench, parsed);
  } catch (const BadBody& bad) {
    return api_error(400, "bad request", bad.detail);
  }
}

}  // namespace wavebench::daemon
