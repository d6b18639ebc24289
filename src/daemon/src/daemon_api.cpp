#include "wavebench/daemon/daemon_api.hpp"

#include <spdlog/spdlog.h>

#include <charconv>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "wavebench/daemon/api_token.hpp"
#include "wavebench/daemon/browser_request.hpp"
#include "wavebench/daemon/console_files.hpp"
#include "wavebench/daemon/live_stream.hpp"
#include "wavebench/daemon/login_throttle.hpp"
#include "wavebench/daemon/low_priority_reads.hpp"
#include "wavebench/daemon/manual_api.hpp"
#include "wavebench/daemon/printable_text.hpp"
#include "wavebench/daemon/request_json.hpp"
#include "wavebench/daemon/run_export_download.hpp"
#include "wavebench/daemon/run_history_query.hpp"
#include "wavebench/daemon/run_trace.hpp"
#include "wavebench/daemon/sample_json.hpp"
#include "wavebench/daemon/servo_words.hpp"
#include "wavebench/daemon/session_table.hpp"
#include "wavebench/procedures/procedure_catalogue.hpp"
#include "wavebench/procedures/product_spec.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::daemon {

namespace {

constexpr std::size_t kDefaultSampleLimit = 1000;
constexpr std::size_t kMaxSampleLimit = 100000;
constexpr std::size_t kDefaultLiveLimit = 1000;

// A bad query parameter, reported as 400 naming the key.
struct BadParameter : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

std::optional<std::uint64_t> unsigned_param(const HttpTarget& target, const std::string& key) {
  const auto it = target.query.find(key);
  if (it == target.query.end()) return std::nullopt;
  std::uint64_t value = 0;
  const auto& text = it->second;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
    throw BadParameter(key + ": got '" + text + "', expected a non-negative integer");
  }
  return value;
}

// Run ids are UTC timestamps, "20261122T045843.123456Z" (run_store.hpp): anything else is not
// a run, and never reaches the file system.
bool looks_like_run_id(const std::string& id) {
  if (id.size() != 23 || id[8] != 'T' || id[15] != '.' || id[22] != 'Z') return false;
  for (std::size_t i = 0; i < 22; ++i) {
    if (i == 8 || i == 15) continue;
    if (id[i] < '0' || id[i] > '9') return false;
  }
  return true;
}

std::string utc_now_text() {
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

// A 503 that says when to come back: the console and the CLI wait that long and retry.
ApiResponse busy(const std::string& detail, int retry_after_s) {
  auto answer = api_error(503, "busy", detail);
  answer.headers.emplace_back("Retry-After", std::to_string(retry_after_s));
  return answer;
}

ApiResponse busy_reading() {
  return busy(std::to_string(DaemonApi::kMaxConcurrentReads) +
                  " reads of run data are in progress; retry shortly",
              1);
}

nlohmann::json description_json(const bench::BenchDescription& d) {
  return {{"name", d.name},
          {"unit_serial", d.unit_serial},
          {"ratio", d.sense.ratio},
          {"direction_sign", d.sense.direction_sign},
          {"sync_period_s", d.sync_period_s},
          {"simulated_clock", d.simulated_clock},
          {"rated_torque_nm", d.rated_torque_nm},
          {"max_brake_torque_nm", d.max_brake_torque_nm},
          {"twin_case", d.twin_case_path}};
}

nlohmann::json nodes_json(const std::vector<bench::AcquisitionStats::NodeHeartbeat>& nodes) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& n : nodes) {
    out.push_back(
        {{"node", n.node},
         {"nmt_state", n.nmt_state.empty() ? nlohmann::json(nullptr) : nlohmann::json(n.nmt_state)},
         {"heartbeat_age_s",
          n.heartbeat_age_s >= 0 ? nlohmann::json(n.heartbeat_age_s) : nlohmann::json(nullptr)},
         {"heartbeats", n.heartbeats},
         {"supervision", n.supervision}});
  }
  return out;
}

nlohmann::json acquisition_json(const bench::AcquisitionStats& a) {
  return {{"syncs_sent", a.syncs_sent},
          {"samples", a.samples},
          {"incomplete_samples", a.incomplete_samples},
          {"sync_late", a.sync_late},
          {"sync_skipped", a.sync_skipped},
          {"bus_load", a.bus_load},
          {"cycles_timed_out", a.cycles_timed_out},
          {"cycles_waited_for_devices", a.cycles_waited_for_devices},
          {"longest_device_wait_s", a.longest_device_wait_s},
          {"late_devices", a.late_devices},
          {"late_frames", a.late_frames},
          {"sync_lateness_p50_s", a.sync_lateness_p50_s},
          {"sync_lateness_p99_s", a.sync_lateness_p99_s},
          {"sync_lateness_max_s", a.sync_lateness_max_s},
          {"bench_time_s", a.bench_time_s},
          {"real_time_s", a.real_time_s},
          {"drive_heartbeats", a.drive_heartbeats},
          {"drive_heartbeat_gap_max_s", a.drive_heartbeat_gap_max_s},
          {"drive_statusword",
           a.drive_statusword ? nlohmann::json(*a.drive_statusword) : nlohmann::json(nullptr)},
          {"drive_state",
           a.drive_state.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.drive_state)},
          {"brake_output_on",
           a.brake_output_on ? nlohmann::json(*a.brake_output_on) : nlohmann::json(nullptr)},
          {"brake_coil_temperature_c", a.brake_coil_temperature_c
                                           ? nlohmann::json(*a.brake_coil_temperature_c)
                                           : nlohmann::json(nullptr)},
          {"brake_status_word",
           a.brake_status_word ? nlohmann::json(*a.brake_status_word) : nlohmann::json(nullptr)},
          {"brake_alarm",
           a.brake_alarm.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.brake_alarm)},
          {"nodes", nodes_json(a.nodes)}};
}

}  // namespace

ApiResponse api_error(int status, const std::string& error, const std::string& detail) {
  return {status, {{"error", error}, {"detail", printable_text(detail, 1000)}}};
}

std::string response_text(const ApiResponse& response) {
  try {
    return response.body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  } catch (const std::exception&) {
    return R"({"error":"internal error","detail":"the answer could not be serialised"})";
  }
}

DaemonApi::DaemonApi(BenchThread& bench, storage::RunStore& store, LiveSampleBuffer& live,
                     std::string token, HostCheck host_check, std::filesystem::path specs_dir,
                     std::shared_ptr<const ConsoleFiles> console, SoftwareIdentity software)
    : bench_(bench),
      store_(store),
      live_(live),
      token_(std::move(token)),
      host_check_(std::move(host_check)),
      specs_dir_(specs_dir.empty() ? procedures::default_specs_dir() : std::move(specs_dir)),
      reads_(std::make_shared<LowPriorityReads>(kMaxConcurrentReads)),
      console_(console ? std::move(console) : std::make_shared<const ConsoleFiles>()),
      software_(std::move(software)),
      sessions_(std::make_shared<SessionTable>()),
      accounts_(std::make_shared<const Accounts>()),
      throttle_(std::make_shared<LoginThrottle>()),
      live_clients_(std::make_shared<LiveStreamClients>(kMaxLiveStreams)),
      downloads_(std::make_shared<CountedSlots>(kMaxDownloads)),
      instance_id_(random_hex_token().substr(0, 16)),
      started_at_(utc_now_text()) {}

void DaemonApi::set_logins(LoginSetup logins) {
  sessions_ = std::make_shared<SessionTable>(SessionTable::kDefaultCapacity, logins.idle_timeout,
                                             nullptr, logins.max_age);
  accounts_ = std::make_shared<const Accounts>(std::move(logins.accounts));
}

ApiResponse DaemonApi::costly(const std::function<ApiResponse()>& read) const {
  auto answer = reads_->run(read);
  return answer ? std::move(*answer) : busy_reading();
}

ApiResponse DaemonApi::handle(const ApiRequest& request) const noexcept {
  try {
    if (request.host.empty()) {
      return api_error(400, "bad request", "Host: missing; expected the daemon's address");
    }
    if (!host_check_.allows(request.host)) {
      return api_error(421, "misdirected request",
                       "Host: got '" + request.host + "', expected " + host_check_.expected() +
                           " (a page of another site must not reach the bench)");
    }
    return route(request);
  } catch (const std::exception& e) {
    return api_error(500, "internal error", e.what());
  } catch (...) {
    return api_error(500, "internal error", "unknown exception");
  }
}

std::span<const ApiRoute> DaemonApi::routes() {
  using R = RouteAuth;
  using C = RouteCost;
  using Call = RouteCall;
  // Private members are reachable from here: the handlers are lambdas of this member function.
  static const ApiRoute table[] = {
      {"GET", "/api/status", R::kNone, C::kCheap,
       [](const DaemonApi& api, const Call&) { return api.status(); }},
      {"GET", "/api/live", R::kNone, C::kCheap,
       [](const DaemonApi& api, const Call& c) { return api.live(c.target); }},
      {"GET", "/api/live/stream", R::kNone, C::kCheap,
       [](const DaemonApi& api, const Call& c) { return api.live_stream(c.target); }},
      // The session checks its own: logging in is how a caller gets a login.
      {"GET", "/api/session", R::kNone, C::kCheap,
       [](const DaemonApi& api, const Call& c) { return api.session(c.request); }},
      {"POST", "/api/session", R::kNone, C::kCheap,
       [](const DaemonApi& api, const Call& c) { return api.session(c.request); }},
      {"DELETE", "/api/session", R::kNone, C::kCheap,
       [](const DaemonApi& api, const Call& c) { return api.session(c.request); }},
      {"POST", "/api/abort", R::kChange, C::kCheap,
       [](const DaemonApi& api, const Call&) { return api.abort_run(); }},
      {"POST", "/api/stop", R::kStop, C::kCheap,
       [](const DaemonApi& api, const Call&) { return api.stop(); }},
      {"POST", "/api/reset", R::kEngineer, C::kCheap,
       [](const DaemonApi& api, const Call&) { return api.reset(); }},
      {"POST", "/api/manual/{action}", R::kChange, C::kCheap,
       [](const DaemonApi& api, const Call& c) {
         return manual_request(api.bench_, c.target.segments[2], c.request.body);
       }},
      {"GET", "/api/procedures", R::kNone, C::kCheap,
       [](const DaemonApi&, const Call&) {
         return ApiResponse{200, procedures::procedures_json()};
       }},
      {"GET", "/api/specs", R::kNone, C::kCheap,
       [](const DaemonApi& api, const Call&) { return api.list_specs(); }},
      {"GET", "/api/fleet/{query}", R::kNone, C::kRead,
       [](const DaemonApi& api, const Call& c) {
         if (!api.fleet_) return api_error(404, "not found", "no results store behind this API");
         return api.fleet_(c.target);
       }},
      {"GET", "/api/bench/check", R::kNone, C::kCheap,
       [](const DaemonApi& api, const Call&) { return api.bench_check(); }},
      {"GET", "/api/runs", R::kNone, C::kCheap,
       [](const DaemonApi& api, const Call& c) { return api.list_runs(c.target); }},
      {"POST", "/api/runs", R::kChange, C::kCheap,
       [](const DaemonApi& api, const Call& c) { return api.start_run(c.request, c.caller); }},
      {"GET", "/api/runs/{id}", R::kNone, C::kRead,
       [](const DaemonApi& api, const Call& c) { return api.run_detail(c.target.segments[2]); }},
      {"GET", "/api/runs/{run}/trace", R::kNone, C::kRead,
       [](const DaemonApi& api, const Call& c) {
         return run_trace(api.store_, c.target.segments[2], c.target);
       }},
      {"GET", "/api/runs/{run}/twin", R::kNone, C::kRead,
       [](const DaemonApi& api, const Call& c) {
         return run_twin_trace(api.store_, c.target.segments[2], c.target);
       }},
      {"GET", "/api/runs/{run}/export", R::kLogin, C::kDownload,
       [](const DaemonApi& api, const Call& c) {
         return run_export_download(api.store_, c.target.segments[2], c.target, c.slot);
       }},
      {"GET", "/api/runs/{id}/samples", R::kNone, C::kRead,
       [](const DaemonApi& api, const Call& c) {
         return api.run_samples(c.target.segments[2], c.target);
       }},
  };
  return table;
}

std::optional<ApiResponse> DaemonApi::refuse(RouteAuth auth, const ApiRequest& request,
                                             SessionIdentity& caller) const {
  switch (auth) {
    case RouteAuth::kNone:
      return std::nullopt;
    case RouteAuth::kStop:
      return refuse_stop(request);
    case RouteAuth::kChange:
      return refuse_change(request, &caller);
    case RouteAuth::kEngineer:
      if (auto refused = refuse_change(request, &caller)) return refused;
      if (caller.role != Role::kEngineer) {
        return api_error(403, "forbidden",
                         "role operator: a reset clears a fault, which is an engineer's call; "
                         "ask an engineer (an account with role engineer)");
      }
      return std::nullopt;
    case RouteAuth::kLogin:
      if (has_login(request)) return std::nullopt;
      return api_error(401, "unauthorized",
                       "a run's samples need a login: log in at /login (the console sends its "
                       "session), or send 'Authorization: Bearer <token>' (the CLI)");
  }
  return api_error(500, "internal error", "a route without a known auth");
}

ApiResponse DaemonApi::route(const ApiRequest& request) const {
  HttpTarget target;
  try {
    target = parse_http_target(request.target);
  } catch (const std::invalid_argument& e) {
    return api_error(400, "bad request", e.what());
  }
  // Names, filters and ids are text: bytes that are not printable UTF-8 can match nothing,
  // and are refused before they reach the index or the file system.
  const auto printable = [](const std::string& text) {
    return is_valid_utf8(text) && printable_text(text, text.size() + 1) == text;
  };
  for (const auto& [key, value] : target.query) {
    if (!printable(key) || !printable(value)) {
      return api_error(400, "bad request",
                       "query '" + key + "': got '" + value + "', expected printable UTF-8 text");
    }
  }
  for (const auto& segment : target.segments) {
    if (!printable(segment)) {
      return api_error(404, "not found", "no resource at " + target.path);
    }
  }
  const auto& seg = target.segments;
  const bool api_path = !seg.empty() && seg[0] == "api";
  std::vector<std::string_view> allowed;
  const ApiRoute* found = nullptr;
  if (api_path) {
    for (const auto& candidate : routes()) {
      if (!route_matches(candidate.pattern, seg)) continue;
      allowed.push_back(candidate.method);
      if (candidate.method == request.method) found = &candidate;
    }
  } else {
    allowed.push_back("GET");  // the console's files
  }
  const auto method_not_allowed = [&](const std::string& detail) {
    auto answer = api_error(405, "method not allowed", detail);
    if (!allowed.empty()) answer.headers.emplace_back("Allow", method_list_text(allowed));
    return answer;
  };
  if (request.method == "OPTIONS") {
    // No CORS preflight is ever granted: a page of another origin cannot send the console's
    // header, nor JSON, to this daemon.
    return method_not_allowed("OPTIONS " + target.path +
                              "; this daemon grants no cross-origin requests");
  }
  if (!api_path) {
    if (request.method != "GET") {
      return method_not_allowed(request.method + " " + target.path + "; expected GET");
    }
    return console_->answer(target);
  }
  if (allowed.empty()) return api_error(404, "not found", "no resource at " + target.path);
  if (!found) {
    return method_not_allowed(request.method + " " + target.path + "; expected " +
                              method_list_text(allowed));
  }
  for (const auto index : run_id_segments(found->pattern)) {
    if (!looks_like_run_id(seg[index]))
      return api_error(404, "not found", "run '" + seg[index] + "' is not a run id");
  }
  try {
    SessionIdentity caller;
    if (auto refused = refuse(found->auth, request, caller)) return std::move(*refused);
    RouteCall call{request, target, caller, nullptr};
    const auto answer = [&] {
      try {
        return found->handler(*this, call);
      } catch (const BadParameter& e) {
        return api_error(400, "bad request", e.what());
      }
    };
    switch (found->cost) {
      case RouteCost::kCheap:
        return answer();
      case RouteCost::kRead:
        return costly(answer);
      case RouteCost::kDownload:
        call.slot = downloads_->admit();
        if (!call.slot) {
          return busy(std::to_string(kMaxDownloads) +
                          " downloads are in progress; retry when one has ended",
                      5);
        }
        return costly(answer);
    }
  } catch (const BadParameter& e) {
    return api_error(400, "bad request", e.what());
  } catch (const std::exception& e) {
    return api_error(500, "internal error", e.what());
  }
  return api_error(500, "internal error", "a route without a known cost");
}

bool DaemonApi::has_login(const ApiRequest& request) const {
  if (bearer_matches(request.authorization, token_)) return true;
  const auto id = cookie_value(request.cookie, session_cookie_name(request.host));
  return !id.empty() && sessions_->use(id).has_value();
}

std::optional<ApiResponse> DaemonApi::refuse_change(const ApiRequest& request,
                                                    SessionIdentity* caller) const {
  if (request.has_origin && !same_origin(request.origin, request.host)) {
    return api_error(403, "forbidden",
                     "Origin: got '" + request.origin + "', expected http://" + request.host +
                         " (a page of another site must not move the bench)");
  }
  if (bearer_matches(request.authorization, token_)) {
    if (caller) *caller = SessionIdentity{};  // the token: automation, acts as an engineer
    return std::nullopt;
  }
  const auto id = cookie_value(request.cookie, session_cookie_name(request.host));
  const auto who = id.empty() ? std::nullopt : sessions_->use(id);
  if (!who) {
    return api_error(401, "unauthorized",
                     "this request moves hardware: send 'Authorization: Bearer <token>' with the "
                     "daemon's token (see its --token-file), or log in at /login");
  }
  if (request.console_request.empty()) {
    return api_error(403, "forbidden",
                     std::string(kConsoleHeader) +
                         ": missing; the console sends it with every change (a form of another "
                         "site cannot)");
  }
  if (caller) *caller = *who;
  return std::nullopt;
}

// The stop needs no session (issue #21): an operator whose session expired, or who never
// logged in, must still be able to stop a moving bench from any console page. What keeps this
// safe against a page of another site the operator has open:
//  - the Host check (host_check.hpp) ran first: a DNS-rebound name never gets here;
//  - an Origin, when sent, must be this daemon's own: a cross-origin fetch or form is refused;
//  - the X-Wavebench-Request header is required: an HTML form cannot send a custom header, and
//    a cross-origin fetch that sets one needs a CORS preflight, which this daemon never grants
//    (OPTIONS is 405, no Access-Control-* header is ever sent), so the request is not sent;
//  - and stopping only makes the bench safer: it ends motion, it never starts any. The worst a
//    local program that can send the header does is stop a run, which it could do by pulling
//    the plug of a loopback-only daemon's machine anyway; it still cannot start one.
// The CLI's way, the token without the header, works as for any change.
std::optional<ApiResponse> DaemonApi::refuse_stop(const ApiRequest& request) const {
  if (request.has_origin && !same_origin(request.origin, request.host)) {
    return api_error(403, "forbidden",
                     "Origin: got '" + request.origin + "', expected http://" + request.host +
                         " (a page of another site must not reach the bench)");
  }
  if (bearer_matches(request.authorization, token_) || !request.console_request.empty()) {
    return std::nullopt;
  }
  return api_error(401, "unauthorized",
                   "send 'Authorization: Bearer <token>' with the daemon's token, or the " +
                       std::string(kConsoleHeader) + " header (the console does)");
}

ApiResponse DaemonApi::session(const ApiRequest& request) const {
  const auto id = cookie_value(request.cookie, session_cookie_name(request.host));
  if (request.method == "GET") {
    const auto who = id.empty() ? std::nullopt : sessions_->use(id);
    ApiResponse answer{200, {{"authenticated", who.has_value()}}};
    answer.body["account"] = who && !who->account.empty() ? nlohmann::json(who->account) : nullptr;
    answer.body["role"] = who ? nlohmann::json(role_name(who->role)) : nullptr;
    answer.body["accounts"] = !accounts_->empty();  // whether the login page asks for a name
    // Renewed on every check: an open console keeps its session.
    if (who)
      answer.headers.emplace_back("Set-Cookie", session_cookie(session_cookie_name(request.host),
                                                               id, sessions_->lifetime().count()));
    return answer;
  }
  if (request.method != "POST" && request.method != "DELETE") {
    return api_error(405, "method not allowed",
                     request.method + " /api/session; expected GET, POST or DELETE");
  }
  if (request.has_origin && !same_origin(request.origin, request.host)) {
    return api_error(403, "forbidden",
                     "Origin: got '" + request.origin + "', expected http://" + request.host);
  }
  if (request.console_request.empty()) {
    return api_error(403, "forbidden",
                     std::string(kConsoleHeader) + ": missing; log in from the console's page");
  }
  if (request.method == "DELETE") {
    if (!id.empty()) sessions_->remove(id);
    ApiResponse answer{200, {{"authenticated", false}}};
    answer.headers.emplace_back("Set-Cookie",
                                session_cookie(session_cookie_name(request.host), "", 0));
    return answer;
  }
  return login(request);
}

ApiResponse DaemonApi::login(const ApiRequest& request) const {
  if (request.body.size() > kMaxLoginBody) {
    return api_error(413, "payload too large",
                     "body: " + std::to_string(request.body.size()) + " bytes, expected at most " +
                         std::to_string(kMaxLoginBody));
  }
  const auto parsed = parse_request_json(request.body);
  if (!parsed.error.empty()) return api_error(400, "bad request", parsed.error);
  const auto& body = parsed.value;
  const auto text = [&](const char* key) -> std::optional<std::string> {
    if (!body.is_object()) return std::nullopt;
    const auto it = body.find(key);
    if (it == body.end() || !it->is_string()) return std::nullopt;
    return it->get<std::string>();
  };
  const auto name = text("name");
  const auto password = text("password");
  const auto token = text("token");
  if (!name && !token) {
    return api_error(400, "bad request",
                     "name: missing; expected {\"name\": ..., \"password\": ...} or "
                     "{\"token\": \"<the daemon's token>\"}");
  }
  if (name && (!valid_account_name(*name) || !password)) {
    return api_error(400, "bad request",
                     !password
                         ? std::string("password: missing; expected a string")
                         : "name: got '" + *name + "', expected 1 to " +
                               std::to_string(kMaxAccountNameLength) + " of A-Z a-z 0-9 . _ -");
  }
  // Failures count per account name and per client: a guesser is slowed whichever it varies.
  std::vector<std::string> keys = {"client:" + request.client};
  if (name) keys.push_back("name:" + *name);
  std::chrono::seconds wait{0};
  for (const auto& key : keys) wait = std::max(wait, throttle_->wait(key));
  // The account name is what the client sent: printable_text() keeps a log line one line of
  // printable text. The password is never logged.
  const auto account_text = name ? "account '" + printable_text(*name, 64) + "'" : "the token";
  const auto client_text = request.client.empty() ? std::string("an unknown client")
                                                  : printable_text(request.client, 64);
  if (wait.count() > 0) {
    spdlog::warn("login refused for {} from {}: throttled, {} s to wait", account_text, client_text,
                 wait.count());
    auto answer = api_error(429, "too many requests",
                            "too many failed logins: retry in " + std::to_string(wait.count()) +
                                " s (each further failure doubles the wait)");
    answer.headers.emplace_back("Retry-After", std::to_string(wait.count()));
    return answer;
  }
  SessionIdentity who;
  bool ok = false;
  if (name) {
    const auto* account = accounts_->find(*name);
    if (account) {
      ok = verify_password(account->password_hash, *password);
      who = {account->name, account->role};
    } else {
      verify_nothing(*password);  // as slow as a wrong password: names are not probed by timing
    }
  } else {
    ok = bearer_matches("Bearer " + *token, token_);
  }
  if (!ok) {
    for (const auto& key : keys) throttle_->failed(key);
    spdlog::warn(
        "login failed for {} from {}: {}", account_text, client_text,
        name ? (accounts_->find(*name) ? "wrong password" : "no such account") : "wrong token");
    return api_error(401, "unauthorized",
                     name ? "name or password: not an account of this daemon (its --accounts file)"
                          : "token: not the daemon's token (see its --token-file)");
  }
  for (const auto& key : keys) throttle_->succeeded(key);
  ApiResponse answer{
      200,
      {{"authenticated", true},
       {"account", who.account.empty() ? nlohmann::json(nullptr) : nlohmann::json(who.account)},
       {"role", role_name(who.role)}}};
  answer.headers.emplace_back(
      "Set-Cookie", session_cookie(session_cookie_name(request.host), sessions_->create(who),
                                   sessions_->lifetime().count()));
  return answer;
}

ApiResponse DaemonApi::live_stream(const HttpTarget& target) const {
  LiveStreamParams params;
  try {
    params = live_stream_params(target);
  } catch (const std::invalid_argument& e) {
    return api_error(400, "bad request", e.what());
  }
  auto slot = live_clients_->admit();
  if (!slot) {
    return api_error(503, "busy",
                     std::to_string(kMaxLiveStreams) +
                         " live streams are open; close one (another console tab) and retry");
  }
  ApiResponse answer;
  answer.content_type = "text/event-stream";
  answer.stream = std::make_shared<LiveStreamFrames>(
      live_, [this] { return status_json(); }, params, std::move(slot));
  return answer;
}

ApiResponse DaemonApi::status() const {
  return {200, status_json()};
}

nlohmann::json DaemonApi::status_json() const {
  const auto s = bench_.status();
  nlohmann::json j;
  j["state"] = daemon_state_name(s.state);
  j["instance"] = {{"id", instance_id_}, {"started_at", started_at_}};
  j["software"] = {{"version", software_.version}, {"commit", software_.commit}};
  j["results_store"] = results_status_ ? results_status_() : nlohmann::json(nullptr);
  j["lifecycle"] = bench::lifecycle_name(s.lifecycle);
  j["bench"] = s.description ? description_json(*s.description) : nlohmann::json(nullptr);
  j["devices"] = nlohmann::json::array();
  auto named = [](const std::vector<storage::ChannelInfo>& list) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& c : list) out.push_back({{"name", c.name}, {"unit", c.unit}});
    return out;
  };
  for (const auto& d : s.devices) {
    j["devices"].push_back({{"name", d.name},
                            {"node", d.node ? nlohmann::json(*d.node) : nlohmann::json(nullptr)},
                            {"channels", named(d.channels)},
                            {"commands", named(d.commands)}});
  }
  j["fault_reason"] =
      s.fault_reason.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.fault_reason);
  j["connect_error"] =
      s.connect_error.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.connect_error);
  if (s.run) {
    j["run"] = {
        {"id", s.run->run_id.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.run->run_id)},
        {"procedure", s.run->procedure},
        {"phase", s.run->phase},
        {"progress", s.run->fraction},
        {"remaining_s",
         s.run->remaining_s < 0 ? nlohmann::json(nullptr) : nlohmann::json(s.run->remaining_s)},
        {"diagnosis_flags", s.run->diagnosis_flags},
        {"points", s.run->points}};
  } else {
    j["run"] = nullptr;
  }
  if (s.last_run) {
    const auto& l = *s.last_run;
    j["last_run"] = {
        {"id", l.run_id},
        {"status", l.status},
        {"reason", l.reason},
        {"procedure", l.procedure},
        {"unit_serial", l.unit_serial},
        {"verdict", l.verdict.empty() ? nlohmann::json(nullptr) : nlohmann::json(l.verdict)}};
  } else {
    j["last_run"] = nullptr;
  }
  // Recorded runs whose post-run work (twin, calibration, results, unit twin, report) goes on
  // in the background, in the order they will finish.
  j["post_runs"] = nlohmann::json::array();
  for (const auto& p : s.post_runs) {
    j["post_runs"].push_back({{"run_id", p.run_id},
                              {"serial", p.unit_serial},
                              {"procedure", p.procedure},
                              {"phase", p.phase},
                              {"progress", p.fraction},
                              {"remaining_s", p.remaining_s < 0 ? nlohmann::json(nullptr)
                                                                : nlohmann::json(p.remaining_s)}});
  }
  j["acquisition"] = s.acquisition ? acquisition_json(*s.acquisition) : nlohmann::json(nullptr);
  j["live_samples"] = live_.total();
  // The newest sample's values for the bench panel (null: not valid in that cycle).
  j["latest"] = nullptr;
  std::optional<storage::SyncSample> newest_sample;
  if (const auto total = live_.total(); total > 0) {
    const auto newest = live_.since(total - 1, 1);
    if (!newest.samples.empty()) {
      const auto& x = newest.samples.back().sample;
      newest_sample = x;
      j["latest"] = {{"time_s", static_cast<double>(x.receive_time_ns) * 1e-9}};
      for (std::size_t i = 0; i < storage::kCoreChannels.size(); ++i)
        j["latest"][std::string(storage::kCoreChannels[i].column)] =
            x.arrived(i) ? nlohmann::json(x.value(i)) : nlohmann::json(nullptr);
    }
  }
  const auto words = servo_words(s, newest_sample);
  j["servo"] = words.servo;
  j["brake"] = words.brake;
  j["manual"] = manual_json(s.manual);
  return j;
}

ApiResponse DaemonApi::start_run(const ApiRequest& request, const SessionIdentity& caller) const {
  const auto parsed = parse_request_json(request.body);
  if (!parsed.error.empty()) return api_error(400, "bad request", parsed.error);
  const auto& body = parsed.value;
  if (!body.is_object()) {
    return api_error(400, "bad request",
                     "body: got '" + printable_text(request.body) +
                         "', expected a JSON object {\"procedure\": ..., \"options\": {...}}");
  }
  for (const auto& [key, value] : body.items()) {
    if (key != "procedure" && key != "options" && key != "twin" && key != "report" &&
        key != "spec" && key != "unit_serial" && key != "operator") {
      return api_error(400, "bad request",
                       key +
                           ": unknown key; expected procedure, options, spec, unit_serial, "
                           "operator, twin or report");
    }
  }
  procedures::RunRequest run;
  const auto procedure = body.find("procedure");
  if (procedure == body.end() || !procedure->is_string()) {
    return api_error(400, "bad request",
                     "procedure: got " +
                         (procedure == body.end() ? std::string("nothing") : procedure->dump()) +
                         ", expected \"static\", \"dynamic\", \"lost-motion\" or \"torsional\"");
  }
  run.procedure = procedure->get<std::string>();
  if (const auto options = body.find("options"); options != body.end()) {
    if (!options->is_object()) {
      return api_error(400, "bad request",
                       "options: got " + options->dump() + ", expected an object");
    }
    run.options = *options;
  }
  for (const auto* key : {"twin", "report"}) {
    if (const auto flag = body.find(key); flag != body.end()) {
      if (!flag->is_boolean()) {
        return api_error(400, "bad request",
                         std::string(key) + ": got " + flag->dump() + ", expected true or false");
      }
      (std::string(key) == "twin" ? run.twin : run.report) = flag->get<bool>();
    }
  }
  for (const auto* key : {"unit_serial", "operator"}) {
    const auto value = body.find(key);
    if (value == body.end() || value->is_null()) continue;
    if (!value->is_string()) {
      return api_error(400, "bad request",
                       std::string(key) + ": got " + value->dump() + ", expected a string");
    }
    (std::string(key) == "operator" ? run.operator_name : run.unit_serial) =
        value->get<std::string>();
  }
  // The run names who started it: the logged-in account, whatever the form said.
  if (!caller.account.empty()) run.operator_name = caller.account;
  if (caller.role != Role::kEngineer && run.options.contains("limits")) {
    return api_error(403, "forbidden",
                     "options.limits: role operator starts runs with the specs folder's limits "
                     "only; changing a spec's limits needs an engineer's account");
  }
  try {
    procedures::check_run_identity(run);
  } catch (const std::invalid_argument& e) {
    return api_error(400, "bad request", e.what());
  }
  if (const auto spec = body.find("spec"); spec != body.end() && !spec->is_null()) {
    if (!spec->is_string()) {
      return api_error(400, "bad request",
                       "spec: got " + spec->dump() + ", expected a spec name (GET /api/specs)");
    }
    try {
      run.spec = procedures::find_product_spec(specs_dir_, spec->get<std::string>());
    } catch (const std::invalid_argument& e) {
      return api_error(400, "bad request", e.what());
    }
  }
  const auto outcome = bench_.start_run(std::move(run));
  switch (outcome.kind) {
    case StartOutcome::Kind::kStarted:
      if (outcome.run_id.empty()) return {202, {{"run_id", nullptr}, {"detail", outcome.detail}}};
      return {201, {{"run_id", outcome.run_id}}};
    case StartOutcome::Kind::kBadRequest:
      return api_error(400, "bad request", outcome.detail);
    case StartOutcome::Kind::kRejected:
      return api_error(409, "conflict", outcome.detail);
    case StartOutcome::Kind::kFailed:
      break;
  }
  auto response = api_error(500, "run failed", outcome.detail);
  if (!outcome.run_id.empty()) response.body["run_id"] = outcome.run_id;
  return response;
}

ApiResponse DaemonApi::abort_run() const {
  const auto s = bench_.status();
  if (!bench_.abort_run("operator abort")) {
    return api_error(409, "conflict", "no run is active");
  }
  nlohmann::json j = {{"aborting", true}};
  j["run_id"] = s.run && !s.run->run_id.empty() ? nlohmann::json(s.run->run_id) : nullptr;
  return {200, j};
}

ApiResponse DaemonApi::stop() const {
  if (!bench_.stop()) return api_error(409, "conflict", "no bench is connected");
  return {200, {{"stopped", true}}};
}

ApiResponse DaemonApi::bench_check() const {
  auto outcome = bench_.check();
  switch (outcome.kind) {
    case CheckOutcome::Kind::kDone:
      return {200, std::move(outcome.report)};
    case CheckOutcome::Kind::kRejected:
      return api_error(409, "conflict", outcome.detail);
    case CheckOutcome::Kind::kUnavailable:
      break;
  }
  return api_error(503, "unavailable", outcome.detail);
}

ApiResponse DaemonApi::reset() const {
  const auto error = bench_.reset();
  if (!error.empty()) return api_error(409, "conflict", error);
  return status();
}

ApiResponse DaemonApi::list_runs(const HttpTarget& target) const {
  storage::RunQuery query;
  try {
    query = parse_run_history_query(target.query);
  } catch (const std::invalid_argument& e) {
    throw BadParameter(e.what());
  }
  return {200, run_history_page(store_, query)};
}

ApiResponse DaemonApi::list_specs() const {
  nlohmann::json specs = nlohmann::json::array();
  nlohmann::json refused = nlohmann::json::array();
  // A spec file that does not load is listed with its reason: the others stay usable.
  for (const auto& name : procedures::product_spec_names(specs_dir_)) {
    try {
      specs.push_back(procedures::load_product_spec(specs_dir_ / (name + ".yaml")).to_json());
    } catch (const std::exception& e) {
      refused.push_back({{"name", name}, {"error", e.what()}});
    }
  }
  return {200, {{"specs", specs}, {"refused", refused}}};
}

ApiResponse DaemonApi::run_detail(const std::string& id) const {
  if (!looks_like_run_id(id))
    return api_error(404, "not found", "run '" + id + "' is not a run id");
  const auto run = store_.find_run(id);
  if (!run) return api_error(404, "not found", "run '" + id + "' is not in the index");
  nlohmann::json j = {{"run", storage::to_json(*run)}};
  const auto paths = store_.paths(id);
  j["results"] = nullptr;
  if (std::ifstream in(paths.results); in) {
    auto results = nlohmann::json::parse(in, nullptr, false);
    if (!results.is_discarded()) j["results"] = std::move(results);
  }
  std::error_code ec;
  const auto size = std::filesystem::file_size(paths.samples, ec);
  j["samples_file_bytes"] = ec ? 0 : size;
  j["report"] = std::filesystem::exists(paths.dir / "report.html")
                    ? nlohmann::json((paths.dir / "report.html").string())
                    : nlohmann::json(nullptr);
  j["dir"] = paths.dir.string();
  // Recorded, its results still being made in the background: where that work is.
  j["post_run"] = nullptr;
  for (const auto& p : bench_.status().post_runs) {
    if (p.run_id != id) continue;
    j["post_run"] = {{"phase", p.phase},
                     {"progress", p.fraction},
                     {"remaining_s",
                      p.remaining_s < 0 ? nlohmann::json(nullptr) : nlohmann::json(p.remaining_s)}};
  }
  return {200, j};
}

ApiResponse DaemonApi::run_samples(const std::string& id, const HttpTarget& target) const {
  const auto from = unsigned_param(target, "from").value_or(0);
  const auto limit = unsigned_param(target, "limit").value_or(kDefaultSampleLimit);
  if (limit > kMaxSampleLimit) {
    throw BadParameter("limit: got '" + std::to_string(limit) + "', expected at most " +
                       std::to_string(kMaxSampleLimit));
  }
  if (!looks_like_run_id(id))
    return api_error(404, "not found", "run '" + id + "' is not a run id");
  if (!store_.find_run(id)) {
    return api_error(404, "not found", "run '" + id + "' is not in the index");
  }
  const auto path = store_.paths(id).samples;
  nlohmann::json j = {{"run_id", id}, {"from", from}};
  nlohmann::json samples = nlohmann::json::array();
  if (!std::filesystem::exists(path)) {
    j["total"] = 0;
    j["samples"] = samples;
    j["torn_tail_bytes"] = 0;
    j["corrupt"] = false;
    return {200, j};
  }
  // Only the page's records are read: a page costs what it returns, however long the run.
  const auto page = storage::read_sample_log_page(path, from, static_cast<std::size_t>(limit));
  std::uint64_t gaps = 0, missed = 0, anomalies = 0, incomplete = 0;
  for (const auto& sample : page.samples) {
    gaps += (sample.flags & storage::kGapBefore) != 0 ? 1 : 0;
    missed += sample.missed_before;
    anomalies += (sample.flags & storage::kCounterAnomaly) != 0 ? 1 : 0;
    incomplete += sample.complete() ? 0 : 1;
  }
  j["total"] = page.total_records;
  j["log_version"] = page.header.version;
  j["channels"] = channels_to_json(page.header.extra_channels);
  j["torn_tail_bytes"] = page.torn_tail_bytes;
  j["corrupt"] = page.corrupt_record;
  j["page_gaps"] = {{"gaps", gaps},
                    {"missed_cycles", missed},
                    {"anomalies", anomalies},
                    {"incomplete_samples", incomplete}};
  // The samples go out as text written directly (append_sample_json): a page of 10,000 as
  // JSON objects took 30-50 ms to build and dump, the text takes a few (issue #12).
  std::vector<std::string> extra_keys;
  for (const auto& c : page.header.extra_channels) {
    extra_keys.push_back(
        nlohmann::json(c.name).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  }
  std::string text = response_text({200, j});
  text.pop_back();  // the closing brace: "samples" goes last
  text += ",\"samples\":[";
  text.reserve(text.size() + page.samples.size() * (300 + 40 * extra_keys.size()));
  for (std::size_t i = 0; i < page.samples.size(); ++i) {
    if (i > 0) text += ',';
    append_sample_json(text, page.samples[i], extra_keys);
  }
  text += "]}\n";
  ApiResponse response;
  response.raw_body = std::move(text);
  return response;
}

ApiResponse DaemonApi::live(const HttpTarget& target) const {
  const auto since = unsigned_param(target, "since").value_or(0);
  const auto limit = unsigned_param(target, "limit").value_or(kDefaultLiveLimit);
  if (limit > kMaxSampleLimit) {
    throw BadParameter("limit: got '" + std::to_string(limit) + "', expected at most " +
                       std::to_string(kMaxSampleLimit));
  }
  const auto slice = live_.since(since, static_cast<std::size_t>(limit));
  const auto extra = bench_.status().extra_channels;
  nlohmann::json samples = nlohmann::json::array();
  for (const auto& s : slice.samples) {
    auto j = sample_to_json(s.sample, extra);
    j["seq"] = s.seq;
    samples.push_back(std::move(j));
  }
  return {200,
          {{"next", slice.next_seq},
           {"missed", slice.missed},
           {"channels", channels_to_json(extra)},
           {"samples", samples}}};
}

}  // namespace wavebench::daemon
