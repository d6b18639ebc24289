#pragma once
// The daemon's HTTP + JSON API as a function from request to response, independent of the
// transport (http_server.hpp carries it over Boost.Beast).
//
//   GET  /api/status                         state, bench, current run, fault, acquisition,
//                                            results store (its outbox)
//   POST /api/runs      {procedure, options, spec, unit_serial, operator}  start  (change)
//   POST /api/abort                           trip the bench: "operator abort" (change)
//   POST /api/stop                            safe state, the run aborted "stopped by operator",
//                                             then inactive again (no reset); needs no session
//                                             (see refuse_stop below)
//   POST /api/reset                           clear a fault / reconnect        (engineer)
//   POST /api/manual/{jog|stop|goto|brake|servo|alive}   the manual panel (manual_api.hpp) (change)
//   POST /api/session   {name, password} | {token}   log in: Set-Cookie wb_session_<port>
//   (HttpOnly,
//                                             Strict); failed logins rate-limited (429)
//   GET  /api/session                         {"authenticated", "account", "role"}; renews it
//   DELETE /api/session                       log out
//   GET  /api/live/stream?window_s=&columns=  server-sent events (live_stream.hpp)
//   GET  /api/runs?unit=&procedure=&spec=&verdict=&status=&from=&to=&offset=&limit=
//                                            a page of the history, newest first, and its total
//                                            (run_history_query.hpp)
//   GET  /api/procedures                      each procedure's options schema
//   GET  /api/specs                           the product specs and their limits
//   GET  /api/runs/{id}                       record + results.json
//   GET  /api/runs/{id}/samples?from=&limit=  a page of samples.wbs (reads only that page;
//                                             page_gaps counts gaps within it)
//   GET  /api/runs/{id}/export?format=mat|hdf5|csv|json   the samples as a file to download
//                                             (run_export_download.hpp), sent in chunks;
//                                             needs a login (session or token); at most
//                                             kMaxDownloads at once, else 503 + Retry-After
//   GET  /api/runs/{id}/trace?channels=&from_s=&to_s=&columns=   min/max per column (run_trace.hpp)
//   GET  /api/runs/{id}/twin?from_s=&to_s=&columns=              the twin's curves (run_trace.hpp)
//   GET  /api/live?since=&limit=              latest samples
//   GET  /api/bench/check                     commissioning check, no motion (409 during a run)
//   GET  /api/fleet/runs|trend|spc?...        the results store (fleet_api.hpp): the shared
//                                             one, else this bench's own
//   GET  /, /history, /app.js, ...            the operator console (console_files.hpp)
//
// A change needs `Authorization: Bearer <token>` (the CLI; acts as an engineer) or, from a
// browser, a live session cookie together with the X-Wavebench-Request header
// (browser_request.hpp); an Origin, when sent, must be this daemon's own. No CORS header is
// ever sent; OPTIONS is 405. The routes above are one table (routes(), api_route.hpp): a path
// it does not know is 404, a method the path lacks 405 with Allow naming the path's methods. A
// session's role (accounts.hpp) limits what it may change: an operator starts runs without
// options.limits (the specs folder's limits only) and cannot reset. Errors are {"error": short
// text, "detail": what exactly}; bad input is 400 naming the key. A request whose Host is not this
// daemon's (host_check.hpp) gets 421 before anything else. Reads that cost in proportion to the
// data (sample pages, run details) run on kMaxConcurrentReads low-priority threads
// (low_priority_reads.hpp); when all are busy the others get 503 at once with Retry-After, so
// status, abort and stop are always answered.

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "wavebench/daemon/accounts.hpp"
#include "wavebench/daemon/api_route.hpp"
#include "wavebench/daemon/bench_thread.hpp"
#include "wavebench/daemon/body_chunks.hpp"
#include "wavebench/daemon/event_stream.hpp"
#include "wavebench/daemon/host_check.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/daemon/live_sample_buffer.hpp"
#include "wavebench/daemon/session_table.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::daemon {

struct ApiRequest {
  std::string method;  // "GET", "POST", ...
  std::string target;  // path and query as sent
  std::string host;    // the Host header; empty when absent
  std::string authorization;
  std::string body;
  std::string cookie;           // the Cookie header (browser_request.hpp)
  std::string origin;           // the Origin header; empty when absent
  bool has_origin = false;      // an empty Origin is still one, and foreign
  std::string console_request;  // the X-Wavebench-Request header
  std::string client;           // the peer's address (login rate limits); empty: unknown
};

struct ApiResponse {
  ApiResponse() = default;
  ApiResponse(int status_code, nlohmann::json json) : status(status_code), body(std::move(json)) {}

  int status = 200;
  nlohmann::json body;
  // A response that is not JSON (a console page, a script, an event stream's first answer):
  // sent as is with its content type instead of `body`.
  std::optional<std::string> raw_body;
  std::string content_type = "application/json";
  std::vector<std::pair<std::string, std::string>> headers;  // extra header fields
  // A server-sent event stream (event_stream.hpp): the header goes out with content_type, then
  // the stream's events until the client closes.
  std::shared_ptr<EventStream> stream;
  // A body sent in chunks as it is made (body_chunks.hpp), after the header with content_type
  // and headers; the connection closes after it.
  std::shared_ptr<BodyChunks> chunks;
};

class LowPriorityReads;
class ConsoleFiles;
class LoginThrottle;
class CountedSlots;
using LiveStreamClients = CountedSlots;

// What /api/status names as the software serving it.
struct SoftwareIdentity {
  std::string version = "unknown";
  std::string commit = "unknown";
};

// Operators by name (accounts.hpp) and how long their sessions last.
struct LoginSetup {
  Accounts accounts;  // empty: only the token logs in
  std::chrono::seconds idle_timeout{30 * 60};
  std::chrono::seconds max_age{12 * 3600};
};

class DaemonApi {
 public:
  static constexpr int kMaxConcurrentReads = 2;
  static constexpr std::size_t kMaxLiveStreams = 8;
  // Export downloads sent at once; more get 503 with Retry-After (each holds a connection and,
  // for mat/hdf5, a scratch file until its client has read it).
  static constexpr std::size_t kMaxDownloads = 2;
  static constexpr std::size_t kMaxLoginBody = 4096;

  // `specs_dir`: the product specs a run may name (empty: procedures::default_specs_dir()).
  DaemonApi(BenchThread& bench, storage::RunStore& store, LiveSampleBuffer& live, std::string token,
            HostCheck host_check = HostCheck(), std::filesystem::path specs_dir = {},
            std::shared_ptr<const ConsoleFiles> console = nullptr, SoftwareIdentity software = {});
  // Thread-safe; may block while a run is being started. Never throws: every failure is an
  // error answer.
  ApiResponse handle(const ApiRequest& request) const noexcept;
  SessionTable& sessions() const { return *sessions_; }
  // GET /api/fleet/...; set before serving (Daemon does: the shared store, else its own).
  void set_fleet_queries(std::function<ApiResponse(const HttpTarget&)> queries) {
    fleet_ = std::move(queries);
  }
  // Accounts and session timeouts; set before serving (else: token only, the defaults).
  void set_logins(LoginSetup logins);
  // `results_store` of GET /api/status (the outbox's state); set before serving.
  void set_results_status(std::function<nlohmann::json()> results_status) {
    results_status_ = std::move(results_status);
  }
  // Every /api route: method, pattern, auth, cost, handler (route() dispatches on it; the tests
  // walk it).
  static std::span<const ApiRoute> routes();

 private:
  ApiResponse route(const ApiRequest& request) const;
  // Why `auth` refuses this request; nothing when it may go ahead, and then `caller` says who.
  std::optional<ApiResponse> refuse(RouteAuth auth, const ApiRequest& request,
                                    SessionIdentity& caller) const;
  ApiResponse costly(const std::function<ApiResponse()>& read) const;
  ApiResponse status() const;
  ApiResponse start_run(const ApiRequest& request, const SessionIdentity& caller) const;
  ApiResponse abort_run() const;
  ApiResponse stop() const;
  ApiResponse reset() const;
  ApiResponse bench_check() const;
  ApiResponse list_runs(const HttpTarget& target) const;
  ApiResponse list_specs() const;
  ApiResponse run_detail(const std::string& id) const;
  ApiResponse run_samples(const std::string& id, const HttpTarget& target) const;
  ApiResponse live(const HttpTarget& target) const;
  ApiResponse live_stream(const HttpTarget& target) const;
  ApiResponse session(const ApiRequest& request) const;
  // Why a state-changing request is refused; nothing when it may go ahead, and then `caller`
  // (when given) says who asks: the token, or a session's account and role.
  std::optional<ApiResponse> refuse_change(const ApiRequest& request,
                                           SessionIdentity* caller = nullptr) const;
  // The stop's own, looser rule (why it is safe: the comment in daemon_api.cpp).
  std::optional<ApiResponse> refuse_stop(const ApiRequest& request) const;
  ApiResponse login(const ApiRequest& request) const;
  // The token, or a live session's cookie (which is renewed).
  bool has_login(const ApiRequest& request) const;
  nlohmann::json status_json() const;

  BenchThread& bench_;
  storage::RunStore& store_;
  LiveSampleBuffer& live_;
  std::string token_;
  HostCheck host_check_;
  std::filesystem::path specs_dir_;
  std::shared_ptr<LowPriorityReads> reads_;
  std::shared_ptr<const ConsoleFiles> console_;  // GET of any path outside /api
  SoftwareIdentity software_;
  std::shared_ptr<SessionTable> sessions_;
  std::shared_ptr<const Accounts> accounts_;
  std::shared_ptr<LoginThrottle> throttle_;
  std::shared_ptr<LiveStreamClients> live_clients_;
  std::shared_ptr<CountedSlots> downloads_;
  // Random per daemon start (GET /api/status "instance"): a console that sees it change knows
  // the daemon restarted, and with it every session ended.
  std::string instance_id_;
  std::string started_at_;  // UTC, to the second
  std::function<ApiResponse(const HttpTarget&)> fleet_;
  std::function<nlohmann::json()> results_status_;
};

// `detail` goes through printable_text(): it may echo what the request sent.
ApiResponse api_error(int status, const std::string& error, const std::string& detail);

// The answer's body as text; never throws (invalid UTF-8 is replaced).
std::string response_text(const ApiResponse& response);

}  // namespace wavebench::daemon
