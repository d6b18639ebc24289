#pragma once
// The CANopen master on one bus: NMT, one SDO client per node (created on first use), heartbeat
// consumers, the EMCY consumer, the SYNC producer, and TPDO receivers by COB-ID. The pieces are
// usable on their own; this only owns them together and routes their events to one set of
// noexcept hooks.

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>

#include "wavebench/can/can_bus.hpp"
#include "wavebench/canopen/emcy.hpp"
#include "wavebench/canopen/heartbeat_consumer.hpp"
#include "wavebench/canopen/nmt.hpp"
#include "wavebench/canopen/sdo_client.hpp"
#include "wavebench/canopen/sync_producer.hpp"

namespace wavebench::canopen {

class Master {
 public:
  struct Hooks {
    std::function<void(NodeId, NmtState)> on_node_state;
    std::function<void(NodeId)> on_heartbeat_lost;
    std::function<void(NodeId)> on_heartbeat_recovered;
    std::function<void(const Emergency&)> on_emcy;
    std::function<void(const can::BusEvent&)> on_bus_event;
  };

  Master(can::CanBus& bus, Hooks hooks,
         std::chrono::milliseconds sdo_timeout = std::chrono::milliseconds(500));
  Master(const Master&) = delete;
  Master& operator=(const Master&) = delete;

  can::CanBus& bus() noexcept { return bus_; }
  NmtMaster& nmt() noexcept { return nmt_; }
  SdoClient& sdo(NodeId node);
  // Starts watching a node's heartbeat (armed on its first heartbeat).
  void consume_heartbeat(NodeId node, std::chrono::milliseconds consumer_time);
  const HeartbeatConsumer* heartbeat(NodeId node) const;

  // The SYNC producer, created on first start.
  SyncProducer& start_sync(std::chrono::microseconds period, std::uint8_t counter_overflow = 0);
  void stop_sync() noexcept;
  SyncProducer* sync() noexcept { return sync_.get(); }

  // Frames with this COB-ID (a TPDO of some node) go to the handler.
  void on_pdo(std::uint32_t cob_id, std::function<void(const can::Frame&)> handler);

 private:
  can::CanBus& bus_;
  Hooks hooks_;
  std::chrono::milliseconds sdo_timeout_;
  NmtMaster nmt_;
  EmcyConsumer emcy_;
  std::map<NodeId, std::unique_ptr<SdoClient>> sdo_;
  std::map<NodeId, std::unique_ptr<HeartbeatConsumer>> heartbeats_;
  std::unique_ptr<SyncProducer> sync_;
  std::map<std::uint32_t, std::function<void(const can::Frame&)>> pdo_handlers_;
  can::CanBus::Subscription pdo_subscription_;
  can::CanBus::Subscription event_subscription_;
};

}  // namespace wavebench::canopen
