#include "wavebench/canopen/frame_description.hpp"

#include <fmt/format.h>

#include "wavebench/canopen/cob_id.hpp"
#include "wavebench/canopen/emcy.hpp"
#include "wavebench/canopen/nmt.hpp"
#include "wavebench/canopen/sdo_abort.hpp"
#include "wavebench/canopen/value_text.hpp"

namespace wavebench::canopen {

namespace {

std::string mux(const can::Frame& f) {
  if (f.len < 4) return "?";
  return fmt::format("{:04X}:{:02X}", f.data[1] | (f.data[2] << 8), f.data[3]);
}

std::uint32_t le32(const can::Frame& f) {
  std::uint32_t v = 0;
  for (std::size_t i = 4; i < 8 && i < f.len; ++i) v |= std::uint32_t{f.data[i]} << (8 * (i - 4));
  return v;
}

std::span<const std::uint8_t> bytes(const can::Frame& f, std::size_t from, std::size_t count) {
  if (from >= f.len) return {};
  return {f.data.data() + from, std::min<std::size_t>(count, f.len - from)};
}

std::string describe_sdo(const can::Frame& f, bool request) {
  if (f.len < 1) return "empty";
  const std::uint8_t c = f.data[0];
  if (c == 0x80) return fmt::format("abort {} {}", mux(f), abort_text(le32(f)));
  const unsigned cs = c >> 5;
  const bool toggle = (c & 0x10) != 0;
  if (request) {
    switch (cs) {
      case 0: {  // download segment
        const std::size_t n = 7U - ((c >> 1) & 7U);
        return fmt::format("download segment t={}{} [{}]", toggle ? 1 : 0, (c & 1) ? " last" : "",
                           hex_bytes(bytes(f, 1, n)));
      }
      case 1: {  // initiate download
        if (c & 0x02) {
          const std::size_t n = (c & 0x01) ? 4U - ((c >> 2) & 3U) : 4U;
          return fmt::format("initiate download {} expedited [{}]", mux(f),
                             hex_bytes(bytes(f, 4, n)));
        }
        return fmt::format("initiate download {} segmented{}", mux(f),
                           (c & 0x01) ? fmt::format(" size {}", le32(f)) : std::string());
      }
      case 2:
        return fmt::format("initiate upload {}", mux(f));
      case 3:
        return fmt::format("upload segment request t={}", toggle ? 1 : 0);
      case 5:
        return fmt::format("block upload {}", mux(f));
      case 6:
        return fmt::format("block download {}", mux(f));
      default:
        return fmt::format("unknown command 0x{:02X}", c);
    }
  }
  switch (cs) {
    case 0: {
      const std::size_t n = 7U - ((c >> 1) & 7U);
      return fmt::format("upload segment t={}{} [{}]", toggle ? 1 : 0, (c & 1) ? " last" : "",
                         hex_bytes(bytes(f, 1, n)));
    }
    case 1:
      return fmt::format("download segment response t={}", toggle ? 1 : 0);
    case 2: {
      if (c & 0x02) {
        const std::size_t n = (c & 0x01) ? 4U - ((c >> 2) & 3U) : 4U;
        const auto b = bytes(f, 4, n);
        return fmt::format("upload response {} expedited [{}] = {}", mux(f), hex_bytes(b),
                           format_value("", b));
      }
      return fmt::format("upload response {} segmented{}", mux(f),
                         (c & 0x01) ? fmt::format(" size {}", le32(f)) : std::string());
    }
    case 3:
      return fmt::format("download response {}", mux(f));
    case 5:
      return fmt::format("block download response {}", mux(f));
    case 6:
      return fmt::format("block upload response {}", mux(f));
    default:
      return fmt::format("unknown command 0x{:02X}", c);
  }
}

}  // namespace

std::string describe_frame(const can::Frame& f) {
  const std::string raw = can::to_string(f);
  if (f.error) return raw + "  error frame";
  if (f.extended) return raw + "  (extended id: not CANopen)";
  if (f.rtr) return raw + "  remote request";
  const std::uint32_t id = f.id;
  const auto node = static_cast<NodeId>(id & 0x7F);
  std::string what;
  if (id == kNmtCobId) {
    if (f.len == 2) {
      const auto cmd = static_cast<NmtCommand>(f.data[0]);
      const auto name = to_string(cmd);
      what = fmt::format(
          "NMT {} {}", name == "unknown" ? fmt::format("0x{:02X}", f.data[0]) : std::string(name),
          f.data[1] == 0 ? std::string("all nodes") : fmt::format("node {}", f.data[1]));
    } else {
      what = "NMT (malformed)";
    }
  } else if (id == kSyncCobId) {
    what = f.len == 0 ? "SYNC" : fmt::format("SYNC counter {}", f.data[0]);
  } else if (id > kEmcyBase && id <= kEmcyBase + 127) {
    if (auto e = decode_emcy(f)) {
      what =
          fmt::format("EMCY node {} {} register 0x{:02X} [{}]", e->node,
                      describe_emcy_code(e->error_code), e->error_register, hex_bytes(e->vendor));
    } else {
      what = fmt::format("EMCY node {} (malformed)", node);
    }
  } else if (id == kTimeCobId) {
    what = "TIME";
  } else if (id >= 0x181 && id <= 0x57F && node != 0) {
    const unsigned fn = (id >> 7);  // 3,5,7,9 TPDO1-4; 4,6,8,10 RPDO1-4
    const bool tpdo = fn % 2 == 1;
    const unsigned number = tpdo ? (fn - 1) / 2 : (fn - 2) / 2;
    what = fmt::format("{}{} node {} [{}]", tpdo ? "TPDO" : "RPDO", number, node,
                       hex_bytes(f.payload()));
  } else if (id > kSdoTxBase && id <= kSdoTxBase + 127) {
    what = fmt::format("SDO node {} response {}", node, describe_sdo(f, false));
  } else if (id > kSdoRxBase && id <= kSdoRxBase + 127) {
    what = fmt::format("SDO node {} request {}", node, describe_sdo(f, true));
  } else if (id > kHeartbeatBase && id <= kHeartbeatBase + 127) {
    if (auto hb = decode_heartbeat(f)) {
      what = fmt::format("HEARTBEAT node {} {}", hb->node, to_string(hb->state));
    } else {
      what = fmt::format("HEARTBEAT node {} (malformed)", node);
    }
  } else {
    what = "unassigned";
  }
  return raw + "  " + what;
}

}  // namespace wavebench::canopen
