#pragma once
// One row of the API's route table (DaemonApi::routes()): which method on which path, who may
// call it, what it costs, and the handler. route() reads the table once per request: an unknown
// path is 404, a known path with another method 405 with Allow, then the auth, then the cost.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace wavebench::daemon {

struct ApiRequest;
struct ApiResponse;
struct HttpTarget;
struct SessionIdentity;
class DaemonApi;

enum class RouteAuth {
  kNone,      // anyone who passed the Host check
  kStop,      // the token, or the console's header (DaemonApi::refuse_stop says why)
  kChange,    // the token, or a session with the console's header (moves hardware)
  kEngineer,  // kChange, and the session's role is engineer
  kLogin,     // the token, or a live session (reads a run's raw samples)
};

enum class RouteCost {
  kCheap,     // answered on the HTTP thread
  kRead,      // on the low-priority read threads; 503 when all are busy
  kDownload,  // a download slot (503 when none is free), then as kRead
};

struct RouteCall {
  const ApiRequest& request;
  const HttpTarget& target;
  const SessionIdentity& caller;  // who asks, for kChange and kEngineer
  std::shared_ptr<void> slot;     // kDownload's slot, held until the download has been sent
};

struct ApiRoute {
  std::string_view method;
  // "/api/runs/{id}/samples": "{run}" matches a run id only (others are 404 after the method
  // check), any other "{...}" one printable segment.
  std::string_view pattern;
  RouteAuth auth;
  RouteCost cost;
  ApiResponse (*handler)(const DaemonApi&, const RouteCall&);
};

// Whether `segments` (a target's path split on '/') has the pattern's shape.
bool route_matches(std::string_view pattern, const std::vector<std::string>& segments);
// The pattern's segments that are "{run}", by index.
std::vector<std::size_t> run_id_segments(std::string_view pattern);
// "GET", "GET or POST", "GET, POST or DELETE": the 405's detail.
std::string method_list_text(const std::vector<std::string_view>& methods);

}  // namespace wavebench::daemon
