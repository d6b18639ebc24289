#pragma once
// A long-lived answer (server-sent events): after the response header, the HTTP server asks
// the stream for its next event every period() and writes it, until the client goes away or
// the stream ends. It is polled on the connection's own strand, never on the bench thread.

#include <chrono>
#include <optional>
#include <string>

namespace wavebench::daemon {

class EventStream {
 public:
  virtual ~EventStream() = default;
  virtual std::chrono::milliseconds period() const = 0;
  // The next event as sent ("data: ...\n\n"); empty: nothing this time; nullopt: the end.
  virtual std::optional<std::string> next() = 0;
};

}  // namespace wavebench::daemon
