#pragma once
// Pre-defined connection set of CiA 301: COB-IDs of every service for a node.

#include <cstdint>

namespace wavebench::canopen {

using NodeId = std::uint8_t;  // 1..127; 0 addresses every node in NMT

inline constexpr std::uint32_t kNmtCobId = 0x000;
inline constexpr std::uint32_t kSyncCobId = 0x080;
inline constexpr std::uint32_t kTimeCobId = 0x100;
inline constexpr std::uint32_t kEmcyBase = 0x080;
inline constexpr std::uint32_t kSdoTxBase = 0x580;  // server -> client
inline constexpr std::uint32_t kSdoRxBase = 0x600;  // client -> server
inline constexpr std::uint32_t kHeartbeatBase = 0x700;
inline constexpr std::uint32_t kCobIdInvalid = 0x80000000U;  // PDO/EMCY COB-ID bit 31

constexpr bool valid_node(unsigned node) noexcept {
  return node >= 1 && node <= 127;
}
constexpr std::uint32_t emcy_cob_id(NodeId node) noexcept {
  return kEmcyBase + node;
}
constexpr std::uint32_t sdo_tx_cob_id(NodeId node) noexcept {
  return kSdoTxBase + node;
}
constexpr std::uint32_t sdo_rx_cob_id(NodeId node) noexcept {
  return kSdoRxBase + node;
}
constexpr std::uint32_t heartbeat_cob_id(NodeId node) noexcept {
  return kHeartbeatBase + node;
}
// PDO numbers 1..4 in the pre-defined set.
constexpr std::uint32_t tpdo_cob_id(unsigned pdo, NodeId node) noexcept {
  return 0x180 + 0x100 * (pdo - 1) + node;
}
constexpr std::uint32_t rpdo_cob_id(unsigned pdo, NodeId node) noexcept {
  return 0x200 + 0x100 * (pdo - 1) + node;
}

}  // namespace wavebench::canopen
