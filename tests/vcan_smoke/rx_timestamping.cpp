#include "rx_timestamping.hpp"

#include <stdexcept>

#include "vcan_fixture.hpp"

namespace wavebench::vcan_smoke {

RxTimestampingOn::RxTimestampingOn(const std::string& ifname, canid_t probe_id, int max_probes)
    : keeper_(ifname) {
  keeper_.set_filters({});
  keeper_.set_timestamps(CanRawSocket::Timestamps::kNanoseconds);

  CanRawSocket a(ifname);
  a.set_timestamps(CanRawSocket::Timestamps::kNanoseconds);
  CanRawSocket b(ifname);
  b.set_timestamps(CanRawSocket::Timestamps::kNanoseconds);
  CanRawSocket tx(ifname);
  for (int i = 0; i < max_probes; ++i) {
    tx.send(classic_frame(probe_id, {}));
    const auto ra = a.receive(kReceiveLimit);
    const auto rb = b.receive(kReceiveLimit);
    if (!ra || !rb || !ra->timestamp_ns || !rb->timestamp_ns) {
      throw std::runtime_error("timestamp probe frame did not arrive with a timestamp");
    }
    if (ra->timestamp_ns->tv_sec == rb->timestamp_ns->tv_sec &&
        ra->timestamp_ns->tv_nsec == rb->timestamp_ns->tv_nsec) {
      return;
    }
  }
  throw std::runtime_error("receive timestamps never became shared between sockets");
}

}  // namespace wavebench::vcan_smoke
