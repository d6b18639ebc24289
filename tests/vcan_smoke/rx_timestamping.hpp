// Keeps receive timestamping switched on for the whole network stack while a test compares
// timestamps between sockets.
//
// The kernel turns stamping at netif_rx on lazily (a deferred static key) when the first socket
// asks for timestamps, and off when the last one closes. Until it is on, each socket stamps
// its own clone of a frame when it reads it, so two sockets report different times for one frame.
#pragma once

#include <string>

#include "can_raw_socket.hpp"

namespace wavebench::vcan_smoke {

class RxTimestampingOn {
 public:
  // Blocks until a probe frame carries one timestamp to two sockets (at most `max_probes`
  // probes); throws when that never happens. Probes use `probe_id`, sent before any of the
  // test's own sockets exist.
  explicit RxTimestampingOn(const std::string& ifname, canid_t probe_id = 0x7FF,
                            int max_probes = 1000);

 private:
  CanRawSocket keeper_;  // no filters: receives nothing, only holds timestamping on
};

}  // namespace wavebench::vcan_smoke
