#include "wavebench/simdevices/canopen_node.hpp"

#include <cstdio>
#include <stdexcept>

#include "wavebench/simdevices/sdo_abort.hpp"

namespace wavebench::simdevices {
namespace {

constexpr std::uint32_t kCobIdInvalid = 0x80000000U;
constexpr std::uint32_t kCobIdExtended = 0x20000000U;
constexpr std::uint32_t kCobIdMask = 0x7FFU;
constexpr std::uint16_t kRpdoComm = 0x1400, kRpdoMap = 0x1600, kTpdoComm = 0x1800,
                        kTpdoMap = 0x1A00;
constexpr std::uint8_t kMaxMappedEntries = 8;
constexpr unsigned kMaxPdoBits = 64;

std::uint16_t comm_index(bool transmit, int number) {
  return static_cast<std::uint16_t>((transmit ? kTpdoComm : kRpdoComm) + number - 1);
}
std::uint16_t map_index(bool transmit, int number) {
  return static_cast<std::uint16_t>((transmit ? kTpdoMap : kRpdoMap) + number - 1);
}

bool valid_transmission_type(std::uint8_t type) {
  return type <= 240 || type >= 254;
}

}  // namespace

CanopenNode::CanopenNode(std::uint8_t node_id, const NodeIdentity& identity, FrameSink sink)
    : node_id_(node_id), sink_(std::move(sink)), sdo_(od_) {
  if (node_id < 1 || node_id > 127) {
    throw std::invalid_argument("node id " + std::to_string(node_id) +
                                " is out of range (expected 1..127)");
  }
  add_communication_objects(identity);
  for (int n = 1; n <= 4; ++n) {
    add_pdo_objects(true, n);
    add_pdo_objects(false, n);
  }
}

void CanopenNode::add_communication_objects(const NodeIdentity& identity) {
  od_.add_value<std::uint32_t>(0x1000, 0, "device type", DataType::kUnsigned32, Access::kConst,
                               identity.device_type);
  od_.add_value<std::uint8_t>(0x1001, 0, "error register", DataType::kUnsigned8, Access::kReadOnly,
                              0, true);
  od_.add_value<std::uint32_t>(0x1005, 0, "COB-ID SYNC", DataType::kUnsigned32, Access::kReadWrite,
                               0x80);
  od_.add_value<std::uint32_t>(0x1006, 0, "communication cycle period", DataType::kUnsigned32,
                               Access::kReadWrite, 0);
  od_.add_string(0x1008, 0, "manufacturer device name", Access::kConst, identity.device_name);
  od_.add_string(0x1009, 0, "manufacturer hardware version", Access::kConst,
                 identity.hardware_version);
  od_.add_string(0x100A, 0, "manufacturer software version", Access::kConst,
                 identity.software_version);
  od_.add_value<std::uint32_t>(0x1014, 0, "COB-ID EMCY", DataType::kUnsigned32, Access::kReadWrite,
                               0x80U + node_id_);
  if (identity.heartbeat_producer) {
    auto& heartbeat = od_.add_value<std::uint16_t>(0x1017, 0, "producer heartbeat time",
                                                   DataType::kUnsigned16, Access::kReadWrite, 0);
    heartbeat.after_write = [this] { restart_heartbeat(now_); };
  } else {
    // Node guarding instead (CiA 301 §7.2.8.3.2.1); the device does not guard its master.
    od_.add_value<std::uint16_t>(0x100C, 0, "guard time", DataType::kUnsigned16, Access::kReadWrite,
                                 0);
    od_.add_value<std::uint8_t>(0x100D, 0, "life time factor", DataType::kUnsigned8,
                                Access::kReadWrite, 0);
  }
  od_.add_value<std::uint8_t>(0x1018, 0, "identity: highest sub-index", DataType::kUnsigned8,
                              Access::kConst, identity.has_serial_number ? 4 : 3);
  od_.add_value<std::uint32_t>(0x1018, 1, "vendor-ID", DataType::kUnsigned32, Access::kReadOnly,
                               identity.vendor_id);
  od_.add_value<std::uint32_t>(0x1018, 2, "product code", DataType::kUnsigned32, Access::kReadOnly,
                               identity.product_code);
  od_.add_value<std::uint32_t>(0x1018, 3, "revision number", DataType::kUnsigned32,
                               Access::kReadOnly, identity.revision);
  if (identity.has_serial_number)
    od_.add_value<std::uint32_t>(0x1018, 4, "serial number", DataType::kUnsigned32,
                                 Access::kReadOnly, identity.serial_number);
}

void CanopenNode::add_pdo_objects(bool transmit, int number) {
  const std::uint16_t comm = comm_index(transmit, number);
  const std::uint16_t map = map_index(transmit, number);
  const std::uint32_t base =
      (transmit ? 0x180U : 0x200U) + 0x100U * static_cast<unsigned>(number - 1);
  const std::uint32_t default_cob = base + node_id_ + (number == 1 ? 0 : kCobIdInvalid);
  const int i = number - 1;

  od_.add_value<std::uint8_t>(comm, 0, "highest sub-index", DataType::kUnsigned8, Access::kConst,
                              transmit ? 5 : 2);
  auto& cob = od_.add_value<std::uint32_t>(comm, 1, "COB-ID", DataType::kUnsigned32,
                                           Access::kReadWrite, default_cob);
  cob.on_write = [this, comm, transmit, i](std::span<const std::uint8_t> data) -> std::uint32_t {
    const auto next = from_le_bytes<std::uint32_t>(data);
    const auto current = od_.get<std::uint32_t>(comm, 1);
    if (next & kCobIdExtended) return sdo_abort::kValueRange;
    // While the PDO is valid only bit 31 may change (CiA 301 §7.5.2.35).
    const bool stays_valid = !(current & kCobIdInvalid) && !(next & kCobIdInvalid);
    if (stays_valid && (next & kCobIdMask) != (current & kCobIdMask)) {
      return sdo_abort::kValueRange;
    }
    if ((next & kCobIdMask) == 0) return sdo_abort::kValueRange;
    auto& rt = transmit ? tpdo_[static_cast<std::size_t>(i)] : rpdo_[static_cast<std::size_t>(i)];
    rt = PdoRuntime{};
    rt.next_event = now_;
    return sdo_abort::kNone;
  };
  auto& type = od_.add_value<std::uint8_t>(comm, 2, "transmission type", DataType::kUnsigned8,
                                           Access::kReadWrite, transmit ? 1 : 1);
  type.on_write = [](std::span<const std::uint8_t> data) -> std::uint32_t {
    return valid_transmission_type(data[0]) ? sdo_abort::kNone : sdo_abort::kValueRange;
  };
  if (transmit) {
    od_.add_value<std::uint16_t>(comm, 3, "inhibit time", DataType::kUnsigned16, Access::kReadWrite,
                                 0);
    od_.add_value<std::uint16_t>(comm, 5, "event timer", DataType::kUnsigned16, Access::kReadWrite,
                                 0);
  }

  auto& count = od_.add_value<std::uint8_t>(map, 0, "number of mapped objects",
                                            DataType::kUnsigned8, Access::kReadWrite, 0);
  count.on_write = [this, transmit, number](std::span<const std::uint8_t> data) {
    return check_mapping_count(transmit, number, data[0]);
  };
  for (std::uint8_t sub = 1; sub <= kMaxMappedEntries; ++sub) {
    auto& entry = od_.add_value<std::uint32_t>(map, sub, "mapped object", DataType::kUnsigned32,
                                               Access::kReadWrite, 0);
    entry.on_write = [this, transmit, comm, map](std::span<const std::uint8_t> data) {
      // Remap order: invalidate the PDO, set sub0 = 0, then the entries.
      if (!(od_.get<std::uint32_t>(comm, 1) & kCobIdInvalid) ||
          od_.get<std::uint8_t>(map, 0) != 0) {
        return sdo_abort::kValueRange;
      }
      const auto value = from_le_bytes<std::uint32_t>(data);
      return value == 0 ? sdo_abort::kNone : check_mapping_entry(transmit, value);
    };
  }
}

std::uint32_t CanopenNode::check_mapping_entry(bool transmit, std::uint32_t entry) const {
  const auto index = static_cast<std::uint16_t>(entry >> 16);
  const auto sub = static_cast<std::uint8_t>(entry >> 8);
  const auto bits = static_cast<std::uint8_t>(entry);
  if (const std::uint32_t abort = od_.locate(index, sub); abort != 0) return abort;
  const OdEntry* e = od_.find(index, sub);
  if (!e->pdo_mappable) return sdo_abort::kNotMappable;
  const bool readable = e->access != Access::kWriteOnly;
  const bool writable = e->access == Access::kReadWrite || e->access == Access::kWriteOnly;
  if (transmit ? !readable : !writable) return sdo_abort::kNotMappable;
  if (bits != 8 * data_type_size(e->type)) return sdo_abort::kNotMappable;
  return sdo_abort::kNone;
}

std::uint32_t CanopenNode::check_mapping_count(bool transmit, int number,
                                               std::uint8_t count) const {
  const std::uint16_t comm = comm_index(transmit, number);
  const std::uint16_t map = map_index(transmit, number);
  if (!(od_.get<std::uint32_t>(comm, 1) & kCobIdInvalid)) return sdo_abort::kValueRange;
  if (count > kMaxMappedEntries) return sdo_abort::kValueRange;
  unsigned total = 0;
  for (std::uint8_t sub = 1; sub <= count; ++sub) {
    const auto entry = od_.get<std::uint32_t>(map, sub);
    if (const std::uint32_t abort = check_mapping_entry(transmit, entry); abort != 0) return abort;
    total += entry & 0xFFU;
  }
  return total > kMaxPdoBits ? sdo_abort::kPdoTooLong : sdo_abort::kNone;
}

std::vector<PdoMappingEntry> CanopenNode::mapping(bool transmit, int number) const {
  const std::uint16_t map = map_index(transmit, number);
  std::vector<PdoMappingEntry> out;
  const auto count = od_.get<std::uint8_t>(map, 0);
  for (std::uint8_t sub = 1; sub <= count; ++sub) {
    const auto v = od_.get<std::uint32_t>(map, sub);
    out.push_back({static_cast<std::uint16_t>(v >> 16), static_cast<std::uint8_t>(v >> 8),
                   static_cast<std::uint8_t>(v)});
  }
  return out;
}

void CanopenNode::set_default_tpdo(int number, std::vector<PdoMappingEntry> entries, bool valid,
                                   std::uint8_t transmission_type) {
  const std::uint16_t comm = comm_index(true, number);
  const std::uint16_t map = map_index(true, number);
  const std::uint32_t cob =
      (od_.get<std::uint32_t>(comm, 1) & ~kCobIdInvalid) | (valid ? 0U : kCobIdInvalid);
  od_.set_default<std::uint32_t>(comm, 1, cob);
  od_.set_default<std::uint8_t>(comm, 2, transmission_type);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    od_.set_default<std::uint32_t>(map, static_cast<std::uint8_t>(k + 1), entries[k].encoded());
  }
  od_.set_default<std::uint8_t>(map, 0, static_cast<std::uint8_t>(entries.size()));
}

void CanopenNode::set_default_rpdo(int number, std::vector<PdoMappingEntry> entries, bool valid,
                                   std::uint8_t transmission_type) {
  const std::uint16_t comm = comm_index(false, number);
  const std::uint16_t map = map_index(false, number);
  const std::uint32_t cob =
      (od_.get<std::uint32_t>(comm, 1) & ~kCobIdInvalid) | (valid ? 0U : kCobIdInvalid);
  od_.set_default<std::uint32_t>(comm, 1, cob);
  od_.set_default<std::uint8_t>(comm, 2, transmission_type);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    od_.set_default<std::uint32_t>(map, static_cast<std::uint8_t>(k + 1), entries[k].encoded());
  }
  od_.set_default<std::uint8_t>(map, 0, static_cast<std::uint8_t>(entries.size()));
}

void CanopenNode::fix_tpdo(const FixedTpdo& fixed) {
  const int number = fixed.number;
  if (number < 1 || number > 4) {
    throw std::invalid_argument("fixed TPDO" + std::to_string(number) + ": expected TPDO1..4");
  }
  unsigned bits = 0;
  for (const auto& e : fixed.mapping) {
    if (od_.find(e.index, e.sub) == nullptr) {
      char object[16];
      std::snprintf(object, sizeof object, "0x%04X:%u", e.index, static_cast<unsigned>(e.sub));
      throw std::invalid_argument("fixed TPDO" + std::to_string(number) + ": object " + object +
                                  " is not in the node's dictionary");
    }
    bits += e.bits;
  }
  if (fixed.mapping.size() > kMaxMappedEntries || bits > kMaxPdoBits) {
    throw std::invalid_argument("fixed TPDO" + std::to_string(number) +
                                ": expected at most 8 entries and 64 bits");
  }
  const std::uint16_t comm = comm_index(true, number);
  const std::uint16_t map = map_index(true, number);
  for (std::uint8_t sub = 1; sub <= kMaxMappedEntries; ++sub)
    od_.set_default<std::uint32_t>(map, sub, 0);
  set_default_tpdo(number, fixed.mapping, !fixed.mapping.empty(), 1);
  for (const int sub : {1, 2, 3, 5})
    od_.find(comm, static_cast<std::uint8_t>(sub))->access = Access::kReadOnly;
  for (std::uint8_t sub = 0; sub <= kMaxMappedEntries; ++sub)
    od_.find(map, sub)->access = Access::kReadOnly;
}

std::uint32_t CanopenNode::sync_cob_id() const {
  return od_.get<std::uint32_t>(0x1005, 0) & kCobIdMask;
}

void CanopenNode::send(std::uint32_t cob_id, std::span<const std::uint8_t> data) {
  if (sink_ && !silent_) sink_(cob_id, data);
}

std::uint16_t CanopenNode::heartbeat_period_ms() const {
  return od_.find(0x1017, 0) != nullptr ? od_.get<std::uint16_t>(0x1017, 0) : 0;
}

void CanopenNode::receive_remote(std::uint32_t cob_id) {
  if (cob_id != 0x700U + node_id_ || nmt_state_ == NmtState::kInitialising) return;
  const std::array<std::uint8_t, 1> answer{static_cast<std::uint8_t>(
      static_cast<std::uint8_t>(nmt_state_) | (guard_toggle_ ? 0x80 : 0))};
  send(0x700U + node_id_, answer);
  guard_toggle_ = !guard_toggle_;
}

void CanopenNode::boot(double now) {
  now_ = now;
  nmt_state_ = NmtState::kInitialising;
  enter_preoperational_after_reset(now);
}

void CanopenNode::enter_preoperational_after_reset(double now) {
  sdo_.reset();
  tpdo_ = {};
  rpdo_ = {};
  const std::array<std::uint8_t, 1> bootup{0x00};
  send(0x700U + node_id_, bootup);
  nmt_state_ = NmtState::kPreOperational;
  guard_toggle_ = false;
  restart_heartbeat(now);
}

void CanopenNode::restart_heartbeat(double now) {
  const auto period_ms = heartbeat_period_ms();
  next_heartbeat_ = now + period_ms * 1e-3;
}

void CanopenNode::send_heartbeat() {
  const std::array<std::uint8_t, 1> state{static_cast<std::uint8_t>(nmt_state_)};
  send(0x700U + node_id_, state);
}

void CanopenNode::advance_to(double now) {
  if (now < now_) return;
  now_ = now;
  if (nmt_state_ == NmtState::kInitialising) return;
  const auto period_ms = heartbeat_period_ms();
  if (period_ms != 0) {
    const double period = period_ms * 1e-3;
    // A tolerance of a microsecond keeps float drift from skipping a beat.
    while (next_heartbeat_ <= now + 1e-6) {
      send_heartbeat();
      next_heartbeat_ += period;
    }
  }
  if (auto abort = sdo_.poll_timeout(now)) send(0x580U + node_id_, *abort);
  if (nmt_state_ != NmtState::kOperational) return;
  for (int n = 1; n <= 4; ++n) {
    const std::uint16_t comm = comm_index(true, n);
    const auto type = od_.get<std::uint8_t>(comm, 2);
    const auto timer_ms = od_.get<std::uint16_t>(comm, 5);
    if ((od_.get<std::uint32_t>(comm, 1) & kCobIdInvalid) || type < 254 || timer_ms == 0) continue;
    auto& rt = tpdo_[static_cast<std::size_t>(n - 1)];
    while (rt.next_event <= now + 1e-6) {
      send_tpdo(n);
      rt.next_event += timer_ms * 1e-3;
    }
  }
}

void CanopenNode::receive(std::uint32_t cob_id, std::span<const std::uint8_t> data, double now) {
  if (now > now_) now_ = now;
  if (cob_id == 0x000) {
    handle_nmt(data, now);
    return;
  }
  if (nmt_state_ == NmtState::kInitialising || nmt_state_ == NmtState::kStopped) return;
  if (cob_id == 0x600U + node_id_) {
    if (auto resp = sdo_.handle(data, now)) send(0x580U + node_id_, *resp);
    return;
  }
  if (nmt_state_ != NmtState::kOperational) return;
  if (cob_id == sync_cob_id()) {
    handle_sync(now);
    return;
  }
  for (int n = 1; n <= 4; ++n) {
    const auto cob = od_.get<std::uint32_t>(comm_index(false, n), 1);
    if (!(cob & kCobIdInvalid) && (cob & kCobIdMask) == cob_id) handle_rpdo(n, data);
  }
}

void CanopenNode::handle_nmt(std::span<const std::uint8_t> data, double now) {
  if (data.size() < 2 || (data[1] != 0 && data[1] != node_id_)) return;
  if (nmt_state_ == NmtState::kInitialising) return;
  switch (data[0]) {
    case 0x01:
      nmt_state_ = NmtState::kOperational;
      break;
    case 0x02:
      if (nmt_state_ != NmtState::kStopped) {
        nmt_state_ = NmtState::kStopped;
        on_nmt_stopped();
      }
      break;
    case 0x80:
      nmt_state_ = NmtState::kPreOperational;
      break;
    case 0x81:  // reset node: application and communication parameters
      od_.restore_defaults(0x0000, 0xFFFF);
      on_reset_application();
      nmt_state_ = NmtState::kInitialising;
      enter_preoperational_after_reset(now);
      break;
    case 0x82:  // reset communication: 0x1000..0x1FFF only
      od_.restore_defaults(0x1000, 0x1FFF);
      nmt_state_ = NmtState::kInitialising;
      enter_preoperational_after_reset(now);
      break;
    default:
      break;
  }
}

void CanopenNode::handle_sync(double now) {
  for (int n = 1; n <= 4; ++n) {
    auto& rt = rpdo_[static_cast<std::size_t>(n - 1)];
    if (rt.has_pending) {
      rt.has_pending = false;
      apply_rpdo(n, rt.pending);
    }
  }
  on_sync(now);
  for (int n = 1; n <= 4; ++n) {
    const std::uint16_t comm = comm_index(true, n);
    if (od_.get<std::uint32_t>(comm, 1) & kCobIdInvalid) continue;
    const auto type = od_.get<std::uint8_t>(comm, 2);
    if (type > 240) continue;
    auto& rt = tpdo_[static_cast<std::size_t>(n - 1)];
    // Type 0 (acyclic synchronous) is sent on every SYNC here: the simulated values change.
    const unsigned every = type == 0 ? 1 : type;
    if (++rt.sync_count >= every) {
      rt.sync_count = 0;
      send_tpdo(n);
    }
  }
}

void CanopenNode::handle_rpdo(int number, std::span<const std::uint8_t> data) {
  unsigned bytes = 0;
  for (const auto& e : mapping(false, number)) bytes += e.bits / 8U;
  if (data.size() < bytes) {
    send_emcy(0x8210, 0x11);  // PDO not processed due to length error
    return;
  }
  const auto type = od_.get<std::uint8_t>(comm_index(false, number), 2);
  if (type <= 240) {
    auto& rt = rpdo_[static_cast<std::size_t>(number - 1)];
    rt.pending.assign(data.begin(), data.end());
    rt.has_pending = true;
  } else {
    apply_rpdo(number, data);
  }
}

void CanopenNode::apply_rpdo(int number, std::span<const std::uint8_t> data) {
  std::size_t offset = 0;
  for (const auto& e : mapping(false, number)) {
    const std::size_t n = e.bits / 8U;
    // A value the object refuses is dropped, as a write by SDO would be.
    (void)od_.write(e.index, e.sub, data.subspan(offset, n));
    offset += n;
  }
}

void CanopenNode::send_tpdo(int number) {
  std::vector<std::uint8_t> frame;
  for (const auto& e : mapping(true, number)) {
    const OdEntry* entry = od_.find(e.index, e.sub);
    if (entry == nullptr) continue;
    const std::size_t n = e.bits / 8U;
    for (std::size_t k = 0; k < n; ++k)
      frame.push_back(k < entry->value.size() ? entry->value[k] : 0);
  }
  send(od_.get<std::uint32_t>(comm_index(true, number), 1) & kCobIdMask, frame);
}

void CanopenNode::send_emcy(std::uint16_t error_code, std::uint8_t error_register,
                            std::array<std::uint8_t, 5> manufacturer) {
  od_.set<std::uint8_t>(0x1001, 0, error_register);
  const auto cob = od_.get<std::uint32_t>(0x1014, 0);
  if ((cob & kCobIdInvalid) || nmt_state_ == NmtState::kInitialising ||
      nmt_state_ == NmtState::kStopped) {
    return;
  }
  const std::array<std::uint8_t, 8> frame{static_cast<std::uint8_t>(error_code & 0xFF),
                                          static_cast<std::uint8_t>(error_code >> 8),
                                          error_register,
                                          manufacturer[0],
                                          manufacturer[1],
                                          manufacturer[2],
                                          manufacturer[3],
                                          manufacturer[4]};
  send(cob & kCobIdMask, frame);
}

}  // namespace wavebench::simdevices
