#include "wavebench/canopen/master.hpp"

#include <stdexcept>
#include <string>

namespace wavebench::canopen {

Master::Master(can::CanBus& bus, Hooks hooks, std::chrono::milliseconds sdo_timeout)
    : bus_(bus),
      hooks_(std::move(hooks)),
      sdo_timeout_(sdo_timeout),
      nmt_(bus),
      emcy_(bus, [this](const Emergency& e) {
        if (hooks_.on_emcy) hooks_.on_emcy(e);
      }) {
  pdo_subscription_ = bus_.on_frame([this](const can::Frame& f) {
    if (f.extended || f.rtr || pdo_handlers_.empty()) return;
    const auto it = pdo_handlers_.find(f.id);
    if (it != pdo_handlers_.end()) it->second(f);
  });
  event_subscription_ = bus_.on_event([this](const can::BusEvent& e) {
    if (hooks_.on_bus_event) hooks_.on_bus_event(e);
  });
}

SdoClient& Master::sdo(NodeId node) {
  auto& slot = sdo_[node];
  if (!slot) slot = std::make_unique<SdoClient>(bus_, node, sdo_timeout_);
  return *slot;
}

void Master::consume_heartbeat(NodeId node, std::chrono::milliseconds consumer_time) {
  heartbeats_[node] = std::make_unique<HeartbeatConsumer>(
      bus_, node, consumer_time,
      HeartbeatConsumer::Hooks{[this](NodeId n, NmtState s) {
                                 if (hooks_.on_node_state) hooks_.on_node_state(n, s);
                               },
                               [this](NodeId n) {
                                 if (hooks_.on_heartbeat_lost) hooks_.on_heartbeat_lost(n);
                               },
                               [this](NodeId n) {
                                 if (hooks_.on_heartbeat_recovered)
                                   hooks_.on_heartbeat_recovered(n);
                               }});
}

const HeartbeatConsumer* Master::heartbeat(NodeId node) const {
  const auto it = heartbeats_.find(node);
  return it == heartbeats_.end() ? nullptr : it->second.get();
}

SyncProducer& Master::start_sync(std::chrono::microseconds period, std::uint8_t counter_overflow) {
  if (sync_) sync_->stop();
  sync_ = std::make_unique<SyncProducer>(bus_, period, counter_overflow);
  sync_->start();
  return *sync_;
}

void Master::stop_sync() noexcept {
  if (sync_) sync_->stop();
}

void Master::on_pdo(std::uint32_t cob_id, std::function<void(const can::Frame&)> handler) {
  if (cob_id > can::kStandardIdMask) {
    throw std::invalid_argument("PDO COB-ID " + std::to_string(cob_id) +
                                ": expected an 11-bit identifier");
  }
  pdo_handlers_[cob_id] = std::move(handler);
}

}  // namespace wavebench::canopen
