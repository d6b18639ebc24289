#pragma once
// Finds the CANopen nodes on a bus without knowing anything about them: every node id gets an
// SDO upload of 0x1000 at once, heartbeats seen meanwhile are noted, and each responder's
// identity object 0x1018 is read. Works with any CiA 301 device.

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "wavebench/can/can_bus.hpp"
#include "wavebench/canopen/cob_id.hpp"
#include "wavebench/canopen/nmt.hpp"

namespace wavebench::canopen {

struct ScannedNode {
  NodeId node = 0;
  std::optional<std::uint32_t> device_type;  // 0x1000
  // 0x1018:01..04 vendor id, product code, revision, serial number (absent sub-indices empty).
  std::array<std::optional<std::uint32_t>, 4> identity{};
  std::optional<NmtState> heartbeat_state;
};

struct ScanOptions {
  std::chrono::milliseconds sdo_timeout{200};
  NodeId first = 1;
  NodeId last = 127;
};

// Blocking: waits in the one event loop until every node has answered or timed out.
std::vector<ScannedNode> scan_nodes(can::CanBus& bus, const ScanOptions& options = {});

}  // namespace wavebench::canopen
