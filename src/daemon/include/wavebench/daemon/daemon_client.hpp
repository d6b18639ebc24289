#pragma once
// The `wavebench` CLI's side of the daemon API: one HTTP/1.1 request per call over
// Boost.Beast, JSON in and out.

#include <chrono>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace wavebench::daemon {

// The daemon is not there (refused, unreachable, timed out, not speaking HTTP).
class DaemonUnreachable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct DaemonEndpoint {
  std::string host;
  std::string port;
};

// "http://HOST:PORT" or "HOST:PORT" (port defaults to 8470). Throws std::invalid_argument
// naming the value and what was expected.
DaemonEndpoint parse_daemon_url(const std::string& url);

struct DaemonReply {
  int status = 0;
  nlohmann::json body;  // null when the body is not JSON

  bool ok() const { return status >= 200 && status < 300; }
  // "error: detail" from an error body, or the status.
  std::string error_text() const;
};

class DaemonClient {
 public:
  // token may be empty for requests that do not move hardware.
  DaemonClient(const std::string& url, std::string token,
               std::chrono::milliseconds timeout = std::chrono::seconds(60));

  // Throw DaemonUnreachable when no HTTP answer comes back.
  DaemonReply get(const std::string& target) const;
  DaemonReply post(const std::string& target,
                   const nlohmann::json& body = nlohmann::json::object()) const;

  const DaemonEndpoint& endpoint() const { return endpoint_; }

 private:
  DaemonReply request(bool post, const std::string& target, const std::string& body) const;

  DaemonEndpoint endpoint_;
  std::string token_;
  std::chrono::milliseconds timeout_;
};

}  // namespace wavebench::daemon
