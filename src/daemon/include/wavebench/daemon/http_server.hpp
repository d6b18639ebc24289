#pragma once
// HTTP/1.1 over Boost.Beast for the daemon's API: accepts on one address, reads each request
// (keep-alive), hands it to the handler and writes back JSON. Runs on the io_context given;
// several threads may run it (each connection has its own strand).

#include <boost/asio/io_context.hpp>
#include <boost/beast/core/error.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "wavebench/daemon/daemon_api.hpp"

namespace wavebench::daemon {

inline constexpr std::uint64_t kRequestBodyLimit = 1 << 20;

// An event stream's client that leaves what was sent unread this long is dropped and its
// slot freed (issue #22: clients that never read held every live-stream slot).
inline constexpr std::chrono::seconds kStalledReaderLimit{10};

// How many event-stream clients were dropped for not reading, since the process started.
std::uint64_t stalled_event_readers_dropped();
inline constexpr std::uint32_t kRequestHeaderLimit = 16 << 10;  // request line included

// The answer to a request Beast could not parse (413 body too large, 431 header too large,
// 400 otherwise), naming what was wrong.
ApiResponse parse_error_answer(boost::beast::error_code ec);

class HttpServer {
 public:
  using Handler = std::function<ApiResponse(const ApiRequest&)>;

  // Binds and listens (port 0 = an ephemeral port). Throws std::runtime_error naming the
  // address and port when it cannot.
  HttpServer(boost::asio::io_context& io, const std::string& address, unsigned short port,
             Handler handler);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  unsigned short port() const;
  void start();  // begins accepting
  void stop();   // stops accepting; open connections end with their current request

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace wavebench::daemon
