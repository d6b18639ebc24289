#include "wavebench/canopen/nmt.hpp"

#include <stdexcept>
#include <string>

namespace wavebench::canopen {

std::string_view to_string(NmtCommand command) noexcept {
  switch (command) {
    case NmtCommand::start:
      return "start";
    case NmtCommand::stop:
      return "stop";
    case NmtCommand::enter_preoperational:
      return "preop";
    case NmtCommand::reset_node:
      return "reset";
    case NmtCommand::reset_communication:
      return "reset-comm";
  }
  return "unknown";
}

std::string_view to_string(NmtState state) noexcept {
  switch (state) {
    case NmtState::boot_up:
      return "boot-up";
    case NmtState::stopped:
      return "stopped";
    case NmtState::operational:
      return "operational";
    case NmtState::preoperational:
      return "pre-operational";
  }
  return "unknown";
}

std::optional<NmtCommand> parse_nmt_command(std::string_view text) noexcept {
  if (text == "start") return NmtCommand::start;
  if (text == "stop") return NmtCommand::stop;
  if (text == "preop") return NmtCommand::enter_preoperational;
  if (text == "reset") return NmtCommand::reset_node;
  if (text == "reset-comm") return NmtCommand::reset_communication;
  return std::nullopt;
}

can::Frame nmt_frame(NmtCommand command, NodeId node) {
  if (node > 127) {
    throw std::invalid_argument("NMT node id " + std::to_string(node) +
                                ": expected 0 (all) or 1..127");
  }
  return can::Frame::make(kNmtCobId, {static_cast<std::uint8_t>(command), node});
}

std::optional<Heartbeat> decode_heartbeat(const can::Frame& frame) noexcept {
  if (frame.extended || frame.rtr || frame.error || frame.len != 1) return std::nullopt;
  if (frame.id <= kHeartbeatBase || frame.id > kHeartbeatBase + 127) return std::nullopt;
  const std::uint8_t raw = frame.data[0] & 0x7F;
  switch (raw) {
    case 0x00:
    case 0x04:
    case 0x05:
    case 0x7F:
      break;
    default:
      return std::nullopt;
  }
  return Heartbeat{static_cast<NodeId>(frame.id - kHeartbeatBase), static_cast<NmtState>(raw),
                   (frame.data[0] & 0x80) != 0};
}

can::Frame heartbeat_frame(NodeId node, NmtState state) {
  return can::Frame::make(heartbeat_cob_id(node), {static_cast<std::uint8_t>(state)});
}

void NmtMaster::send(NmtCommand command, NodeId node, std::error_code& ec) noexcept {
  if (node > 127) {
    ec = std::make_error_code(std::errc::invalid_argument);
    return;
  }
  bus_.send(can::Frame::make(kNmtCobId, {static_cast<std::uint8_t>(command), node}), ec);
}

void NmtMaster::send(NmtCommand command, NodeId node) {
  bus_.send(nmt_frame(command, node));
}

}  // namespace wavebench::canopen
