#pragma once
// HTTP/1.1 over Boost.Beast for the daemon's API: accepts on one address, reads each request
// (keep-alive), hands it to the handler and writes back JSON. Runs on the io_context given;
// several threads may run it (each connection has its own strand).

#include <boost/asio/io_context.hpp>
#include <functional>
#include <memory>
#include <string>

#include "wavebench/daemon/daemon_api.hpp"

namespace wavebench::daemon {

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
