#include "wavebench/canopen/node_scanner.hpp"

#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "wavebench/can/event_loop.hpp"
#include "wavebench/canopen/sdo_client.hpp"

namespace wavebench::canopen {

std::vector<ScannedNode> scan_nodes(can::CanBus& bus, const ScanOptions& options) {
  if (!valid_node(options.first) || !valid_node(options.last) || options.first > options.last) {
    throw std::invalid_argument("scan node range " + std::to_string(options.first) + ".." +
                                std::to_string(options.last) +
                                ": expected 1 <= first <= last <= 127");
  }
  std::map<NodeId, ScannedNode> found;
  auto heartbeat_sub = bus.on_frame([&](const can::Frame& f) {
    if (auto hb = decode_heartbeat(f)) {
      if (hb->node < options.first || hb->node > options.last) return;
      auto& n = found[hb->node];
      n.node = hb->node;
      n.heartbeat_state = hb->state;
    }
  });
  std::vector<std::unique_ptr<SdoClient>> clients;
  int pending = 0;
  for (unsigned id = options.first; id <= options.last; ++id) {
    auto client = std::make_unique<SdoClient>(bus, static_cast<NodeId>(id), options.sdo_timeout);
    // A node that never answers has no SDO server to abort; a silent scan keeps the bus quiet.
    client->set_abort_on_timeout(false);
    auto* c = client.get();
    ++pending;
    c->async_upload(0x1000, 0, [&, c](std::error_code ec, std::vector<std::uint8_t> data) {
      auto finish_node = [&] { --pending; };
      // Any SDO answer, even an abort, proves the node is there.
      if (ec && ec != make_error_code(SdoAbort::timeout)) {
        found[c->node()].node = c->node();
      } else if (!ec) {
        auto& n = found[c->node()];
        n.node = c->node();
        if (data.size() == 4) {
          n.device_type = static_cast<std::uint32_t>(data[0] | data[1] << 8 | data[2] << 16 |
                                                     static_cast<std::uint32_t>(data[3]) << 24);
        }
      }
      if (found.count(c->node()) != 0) {
        ++pending;
        // Identity: queued on the same client, answered in order.
        for (std::uint8_t sub = 1; sub <= 4; ++sub) {
          c->async_upload(
              0x1018, sub, [&, c, sub](std::error_code e2, std::vector<std::uint8_t> d2) {
                if (!e2 && d2.size() == 4) {
                  found[c->node()].identity[sub - 1] = static_cast<std::uint32_t>(
                      d2[0] | d2[1] << 8 | d2[2] << 16 | static_cast<std::uint32_t>(d2[3]) << 24);
                }
                if (sub == 4) --pending;
              });
        }
      }
      finish_node();
    });
    clients.push_back(std::move(client));
  }
  can::run_until(bus.context(), [&pending] { return pending == 0; });
  std::vector<ScannedNode> out;
  for (auto& [id, n] : found) out.push_back(n);
  return out;
}

}  // namespace wavebench::canopen
