#pragma once
// A simulated CANopen slave (CiA 301): object dictionary with the communication objects, SDO
// server, NMT state machine, heartbeat producer, EMCY producer, and four TPDOs and RPDOs with
// mapping configurable by SDO. It speaks in COB-IDs and payload bytes, so it does not depend on
// any transport; SimulatedBench connects it to a CAN bus. Device profiles derive from it.

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "wavebench/simdevices/object_dictionary.hpp"
#include "wavebench/simdevices/sdo_server.hpp"

namespace wavebench::simdevices {

enum class NmtState : std::uint8_t {  // the heartbeat's state byte
  kInitialising = 0x00,
  kStopped = 0x04,
  kOperational = 0x05,
  kPreOperational = 0x7F,
};

struct NodeIdentity {
  std::uint32_t device_type = 0;  // 0x1000
  std::string device_name;        // 0x1008
  std::string hardware_version;   // 0x1009
  std::string software_version;   // 0x100A
  std::uint32_t vendor_id = 0;    // 0x1018:01..04
  std::uint32_t product_code = 0;
  std::uint32_t revision = 0;
  std::uint32_t serial_number = 0;
  bool has_serial_number = true;  // 0x1018:4 is optional in CiA 301 (sub0 = 3 without it)
  // false: a device without a heartbeat producer (no 0x1017 at all); it is supervised by node
  // guarding (0x100C guard time, 0x100D life time factor, answers to remote frames on 0x700+id).
  bool heartbeat_producer = true;
};

// A frame leaving the node: COB-ID (11 bit) and 0..8 data bytes.
using FrameSink = std::function<void(std::uint32_t cob_id, std::span<const std::uint8_t> data)>;

// One mapped object of a PDO: index, sub-index, length in bits (CiA 301 mapping entry).
struct PdoMappingEntry {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::uint8_t bits = 0;
  std::uint32_t encoded() const {
    return (static_cast<std::uint32_t>(index) << 16) | (static_cast<std::uint32_t>(sub) << 8) |
           bits;
  }
};

// A TPDO a device does not let a master remap (issue 20): read-only communication and mapping
// parameters, as some real devices have (a Faulhaber EDS declares them so).
struct FixedTpdo {
  int number = 1;                        // 1..4
  std::vector<PdoMappingEntry> mapping;  // empty: the PDO stays disabled (COB-ID bit 31 set)
};

class CanopenNode {
 public:
  CanopenNode(std::uint8_t node_id, const NodeIdentity& identity, FrameSink sink);
  virtual ~CanopenNode() = default;
  CanopenNode(const CanopenNode&) = delete;
  CanopenNode& operator=(const CanopenNode&) = delete;

  // Power on: Initialising, boot-up message, Pre-operational.
  void boot(double now);
  // A frame from the bus at time `now` [s]. The node ignores frames that are not for it.
  void receive(std::uint32_t cob_id, std::span<const std::uint8_t> data, double now);
  // A remote frame from the bus: on 0x700 + id it is a node-guarding request, answered with
  // the NMT state and the toggle bit (0 first after boot-up or reset, then alternating).
  void receive_remote(std::uint32_t cob_id);
  // A silent node sends nothing at all (a cut cable, a dead device): for tests of its loss.
  void set_silent(bool silent) noexcept { silent_ = silent; }
  bool silent() const noexcept { return silent_; }
  // Time-driven work up to `now`: heartbeat, event-timer TPDOs, SDO timeouts.
  void advance_to(double now);

  NmtState nmt_state() const { return nmt_state_; }
  std::uint8_t node_id() const { return node_id_; }
  ObjectDictionary& od() { return od_; }
  const ObjectDictionary& od() const { return od_; }
  std::uint32_t sync_cob_id() const;

  // Emergency message (CiA 301 §7.2.7); also sets 0x1001. Code 0 clears the error register.
  void send_emcy(std::uint16_t error_code, std::uint8_t error_register,
                 std::array<std::uint8_t, 5> manufacturer = {});

 protected:
  // Device profiles hook in here. on_sync runs after synchronous RPDOs were applied and
  // before the TPDOs are sent: the moment the device latches its inputs.
  virtual void on_sync(double /*now*/) {}
  virtual void on_reset_application() {}
  // The node just entered NMT stopped (by an NMT command): a profile's "connection abort".
  virtual void on_nmt_stopped() {}

  // Factory PDO configuration (becomes the default restored by NMT resets).
  void set_default_tpdo(int number, std::vector<PdoMappingEntry> mapping, bool valid,
                        std::uint8_t transmission_type = 1);
  void set_default_rpdo(int number, std::vector<PdoMappingEntry> mapping, bool valid,
                        std::uint8_t transmission_type = 1);
  // Makes TPDO `fixed.number` fixed: its mapping, the pre-defined COB-ID (valid unless the
  // mapping is empty), synchronous transmission type 1, and every communication and mapping
  // sub-index read-only (an SDO write answers 06010002). Throws std::invalid_argument for an
  // entry the dictionary does not have, or a mapping over 8 entries or 64 bits.
  void fix_tpdo(const FixedTpdo& fixed);

  void send(std::uint32_t cob_id, std::span<const std::uint8_t> data);

 private:
  struct PdoRuntime {
    unsigned sync_count = 0;
    double next_event = 0;
    std::vector<std::uint8_t> pending;  // synchronous RPDO data waiting for the next SYNC
    bool has_pending = false;
  };

  void add_communication_objects(const NodeIdentity& identity);
  void add_pdo_objects(bool transmit, int number);
  void handle_nmt(std::span<const std::uint8_t> data, double now);
  void enter_preoperational_after_reset(double now);
  void handle_sync(double now);
  void handle_rpdo(int number, std::span<const std::uint8_t> data);
  void apply_rpdo(int number, std::span<const std::uint8_t> data);
  void send_tpdo(int number);
  std::uint32_t check_mapping_entry(bool transmit, std::uint32_t entry) const;
  std::uint32_t check_mapping_count(bool transmit, int number, std::uint8_t count) const;
  std::vector<PdoMappingEntry> mapping(bool transmit, int number) const;
  void send_heartbeat();
  std::uint16_t heartbeat_period_ms() const;  // 0x1017, 0 without one
  void restart_heartbeat(double now);

  std::uint8_t node_id_;
  FrameSink sink_;
  ObjectDictionary od_;
  SdoServer sdo_;
  NmtState nmt_state_ = NmtState::kInitialising;
  double now_ = 0;
  double next_heartbeat_ = 0;
  bool guard_toggle_ = false;
  bool silent_ = false;
  std::array<PdoRuntime, 4> tpdo_{};
  std::array<PdoRuntime, 4> rpdo_{};
};

}  // namespace wavebench::simdevices
