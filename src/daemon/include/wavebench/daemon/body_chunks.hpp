#pragma once
// An answer too large to hold whole (a run's export): the HTTP server sends the header, then
// asks for one chunk at a time and writes it (HTTP/1.1 chunked transfer coding) before asking
// for the next, so at most one chunk is in memory per download. next() runs on the
// connection's own strand: each call must be short (one page of samples, one read of a file),
// so the threads that answer /api/status are never held for long.

#include <optional>
#include <string>

namespace wavebench::daemon {

class BodyChunks {
 public:
  virtual ~BodyChunks() = default;
  // The next piece of the body (never empty); nullopt at the end. Throws when the body cannot
  // be made: the connection is then closed without the last chunk, so the client sees a
  // truncated transfer, never a complete-looking file.
  virtual std::optional<std::string> next() = 0;
};

}  // namespace wavebench::daemon
