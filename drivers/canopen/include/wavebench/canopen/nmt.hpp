#pragma once
// NMT master commands and the node states heartbeats report (CiA 301 §7.2.8).

#include <cstdint>
#include <optional>
#include <string_view>

#include "wavebench/can/can_bus.hpp"
#include "wavebench/canopen/cob_id.hpp"

namespace wavebench::canopen {

enum class NmtCommand : std::uint8_t {
  start = 0x01,
  stop = 0x02,
  enter_preoperational = 0x80,
  reset_node = 0x81,
  reset_communication = 0x82,
};

enum class NmtState : std::uint8_t {
  boot_up = 0x00,
  stopped = 0x04,
  operational = 0x05,
  preoperational = 0x7F,
};

std::string_view to_string(NmtCommand command) noexcept;
std::string_view to_string(NmtState state) noexcept;
// "start", "stop", "preop", "reset", "reset-comm" as the CLI spells them.
std::optional<NmtCommand> parse_nmt_command(std::string_view text) noexcept;

can::Frame nmt_frame(NmtCommand command, NodeId node);  // node 0 = all nodes
// A heartbeat/boot-up frame's node and state; nullopt for anything else.
struct Heartbeat {
  NodeId node;
  NmtState state;
  bool toggle;  // node guarding's toggle bit (always 0 in heartbeats)
};
std::optional<Heartbeat> decode_heartbeat(const can::Frame& frame) noexcept;
can::Frame heartbeat_frame(NodeId node, NmtState state);

class NmtMaster {
 public:
  explicit NmtMaster(can::CanBus& bus) : bus_(bus) {}
  NmtMaster(const NmtMaster&) = delete;
  NmtMaster& operator=(const NmtMaster&) = delete;
  void send(NmtCommand command, NodeId node);  // throws std::system_error
  void send(NmtCommand command, NodeId node, std::error_code& ec) noexcept;

 private:
  can::CanBus& bus_;
};

}  // namespace wavebench::canopen
