#pragma once
// The `wavebench` CLI's side of the daemon API: one HTTP/1.1 request per call over
// Boost.Beast, JSON in and out.

#include <chrono>
#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace wavebench::daemon {

// The daemon is not there (refused, unreachable, timed out, not speaking HTTP, not answering
// with its JSON).
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
  nlohmann::json body;     // null when the body is not JSON
  int retry_after_s = -1;  // the Retry-After header in seconds; -1 when absent

  bool ok() const { return status >= 200 && status < 300; }
  // "error: detail" from an error body, or the status.
  std::string error_text() const;
};

class DaemonClient {
 public:
  static constexpr std::size_t kMaxReplyBytes = 256u << 20;
  static constexpr std::chrono::milliseconds kDefaultConnectTimeout{5000};
  // Covers a start request, which the daemon answers once the run has named itself (<= 30 s).
  static constexpr std::chrono::milliseconds kDefaultTimeout{45000};

  // token may be empty for requests that do not move hardware. `timeout` bounds sending the
  // request and reading the whole answer; `connect_timeout` bounds the connection.
  DaemonClient(const std::string& url, std::string token,
               std::chrono::milliseconds timeout = kDefaultTimeout,
               std::chrono::milliseconds connect_timeout = kDefaultConnectTimeout);

  // A GET answered 503 "busy" (the daemon's readers or download slots are all taken) is sent
  // again after Retry-After seconds (else a pause from 0.25 s doubling to 4 s), until
  // `busy_for` has passed; `notice` is told what is waited for before each pause. A GET only:
  // it changes nothing, so sending it twice is harmless. Zero: no retry.
  static constexpr std::chrono::milliseconds kDefaultBusyWait{120000};
  void retry_busy(std::chrono::milliseconds busy_for,
                  std::function<void(const std::string&)> notice) {
    busy_for_ = busy_for;
    busy_notice_ = std::move(notice);
  }

  // Throw DaemonUnreachable when no answer comes back in time, or when the answer is not the
  // daemon's JSON object.
  DaemonReply get(const std::string& target) const;
  DaemonReply post(const std::string& target,
                   const nlohmann::json& body = nlohmann::json::object()) const;

  const DaemonEndpoint& endpoint() const { return endpoint_; }

 private:
  DaemonReply request(bool post, const std::string& target, const std::string& body) const;

  DaemonEndpoint endpoint_;
  std::string token_;
  std::chrono::milliseconds timeout_;
  std::chrono::milliseconds connect_timeout_;
  std::chrono::milliseconds busy_for_{0};
  std::function<void(const std::string&)> busy_notice_;
};

}  // namespace wavebench::daemon
