#include "wavebench/bench/bench_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "wavebench/bench/bench_devices.hpp"
#include "wavebench/bench/drive_unit_statement.hpp"
#include "wavebench/bench/units_motion_check.hpp"
#include "wavebench/canopen/cob_id.hpp"
#include "wavebench/canopen/nmt.hpp"
#include "wavebench/canopen/pdo.hpp"
#include "wavebench/canopen/sdo_abort.hpp"
#include "wavebench/modbus/modbus_endpoint.hpp"

namespace wavebench::bench {
namespace {

using canopen::SdoAbort;

std::string hex32(std::uint32_t v) {
  return fmt::format("0x{:08X}", v);
}

std::uint32_t le32(const std::vector<std::uint8_t>& b) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < b.size() && i < 4; ++i) v |= std::uint32_t{b[i]} << (8 * i);
  return v;
}

std::string device_label(const BenchCanopenDevice& d) {
  return fmt::format("{} (node {})", d.name, d.node);
}

bool is_abort(const std::error_code& ec, SdoAbort code) {
  return ec == canopen::make_error_code(code);
}

class Check {
 public:
  Check(CanopenBench& bench, const CheckOptions& options)
      : bench_(bench), config_(bench.config()), options_(options) {
    report_.bench = config_.description.name;
  }

  CheckReport run() {
    const auto devices = canopen_devices(config_);
    std::set<std::uint8_t> answering;
    for (const auto& d : devices) {
      eds_row(d);
      if (node_rows(d)) answering.insert(d.node);
    }
    brake_row();
    const std::string not_connected = connect_if_asked();
    if (!not_connected.empty()) {
      for (const auto& d : devices) {
        add(device_label(d), "PDO mapping", false, "not checked: " + not_connected);
        add(device_label(d), "heartbeat", false, "not checked: " + not_connected);
      }
      add("bus", "SYNC round trip", false, "not checked: " + not_connected);
      add("bus", "bus load", false, "not checked: " + not_connected);
    } else {
      for (const auto& d : devices) pdo_row(d, answering.contains(d.node));
      observe(devices);
    }
    units_row(devices.front(), answering.contains(devices.front().node));
    return std::move(report_);
  }

 private:
  void add(std::string device, std::string item, bool ok, std::string detail) {
    report_.rows.push_back({std::move(device), std::move(item), ok, std::move(detail)});
  }

  void eds_row(const BenchCanopenDevice& d) {
    if (!d.expect->eds) {
      add(device_label(d), "EDS", true, "none named (" + d.config_key + ".eds)");
      return;
    }
    const auto problems = canopen::check_against_eds(d.used, *d.expect->eds);
    const auto file = d.expect->eds_path.filename().string();
    if (problems.empty()) {
      add(device_label(d), "EDS", true,
          fmt::format("{}: all {} used objects agree (type, access, PDO mapping)", file,
                      d.used.size()));
    } else {
      std::string text = file + ": ";
      for (std::size_t i = 0; i < problems.size(); ++i) text += (i ? "; " : "") + problems[i];
      add(device_label(d), "EDS", false, text);
    }
    eds_warnings_row(d, file);
  }

  // What the EDS reader tolerated: not red (an object the bench uses and could not be read is
  // already red above), but shown, the first few only so the row stays readable.
  void eds_warnings_row(const BenchCanopenDevice& d, const std::string& file) {
    const auto& warnings = d.expect->eds->warnings();
    if (warnings.empty()) return;
    constexpr std::size_t kShown = 5;
    std::string text =
        fmt::format("{}: {} warning{}: ", file, warnings.size(), warnings.size() == 1 ? "" : "s");
    for (std::size_t i = 0; i < warnings.size() && i < kShown; ++i)
      text += (i ? "; " : "") + warnings[i];
    if (warnings.size() > kShown) text += fmt::format("; and {} more", warnings.size() - kShown);
    add(device_label(d), "EDS warnings", true, text);
  }

  // Node answers, device type, identity, each used object. False when the node is silent.
  bool node_rows(const BenchCanopenDevice& d) {
    auto& sdo = bench_.master().sdo(d.node);
    const auto label = device_label(d);
    std::error_code ec;
    const auto type_bytes = sdo.upload(0x1000, 0, ec);
    if (ec) {
      add(label, "node answers", false,
          fmt::format("no SDO answer from node {} (can.nodes.{}): {}", d.node, d.config_key,
                      ec.message()));
      return false;
    }
    add(label, "node answers", true, "SDO upload of 0x1000 answered");

    const auto device_type = le32(type_bytes);
    std::string type_problem;
    if (type_bytes.size() != 4) {
      type_problem = fmt::format("0x1000 is {} bytes, expected 4", type_bytes.size());
    } else if (d.profile != 0 && (device_type & 0xFFFFU) != d.profile) {
      type_problem = fmt::format("0x1000 = {}: profile {} (0x{:04X}), expected CiA {} (0x{:04X})",
                                 hex32(device_type), device_type & 0xFFFFU, device_type & 0xFFFFU,
                                 d.profile, d.profile);
    } else if (d.expect->eds) {
      if (const auto* o = d.expect->eds->find(0x1000, 0)) {
        const auto expected = d.expect->eds->default_integer(*o, d.node);
        if (expected && static_cast<std::uint32_t>(*expected) != device_type)
          type_problem = fmt::format("0x1000 = {}, the EDS says {}", hex32(device_type),
                                     hex32(static_cast<std::uint32_t>(*expected)));
      }
    }
    add(label, "device type", type_problem.empty(),
        type_problem.empty() ? "0x1000 = " + hex32(device_type) : type_problem);

    identity_row(d, sdo);
    for (const auto& u : d.used) object_row(d, sdo, u);
    return true;
  }

  // 0x1018 against the config's `identity:` and against the EDS's [DeviceInfo]: a device that
  // is not the one its EDS describes is red, naming both values. Sub-indices 2..4 are optional
  // in CiA 301: an absent one is noted, not red. The revision's minor half (low 16 bits) means
  // "same behaviour" in CiA 301, so only its major half must match the EDS.
  void identity_row(const BenchCanopenDevice& d, canopen::SdoClient& sdo) {
    struct Field {
      std::uint8_t sub;
      const char* name;
      const char* key;
      const std::optional<std::uint32_t>* expected;
      const char* eds_key;
      std::optional<std::uint32_t> eds;
    };
    const auto& id = d.expect->identity;
    const auto* eds = d.expect->eds ? &*d.expect->eds : nullptr;
    const auto file = d.expect->eds_path.filename().string();
    Field fields[] = {{1, "vendor-ID", "vendor_id", &id.vendor_id, "VendorNumber",
                       eds ? eds->vendor_number() : std::nullopt},
                      {2, "product code", "product_code", &id.product_code, "ProductNumber",
                       eds ? eds->product_number() : std::nullopt},
                      {3, "revision", "revision", &id.revision, "RevisionNumber",
                       eds ? eds->revision_number() : std::nullopt},
                      {4, "serial", "serial_number", &id.serial_number, nullptr, std::nullopt}};
    std::string seen;
    std::string wrong;
    std::string notes;
    auto append = [](std::string& to, const std::string& what) {
      to += (to.empty() ? "" : "; ") + what;
    };
    for (const auto& f : fields) {
      std::error_code ec;
      const auto v = sdo.read<std::uint32_t>(0x1018, f.sub, ec);
      if (ec) {
        const bool absent = is_abort(ec, SdoAbort::no_object) ||
                            is_abort(ec, SdoAbort::no_sub_index) ||
                            is_abort(ec, SdoAbort::write_only);
        if (f.sub != 1 && absent && !*f.expected) {
          append(notes, fmt::format("0x1018:{} {} absent (optional)", f.sub, f.name));
        } else {
          append(wrong, fmt::format("0x1018:{} {} unreadable: {}", f.sub, f.name, ec.message()));
        }
        continue;
      }
      seen += fmt::format("{}{} {}", seen.empty() ? "" : ", ", f.name, hex32(v));
      if (*f.expected && **f.expected != v) {
        append(wrong, fmt::format("{} {}, expected {} ({}.identity.{})", f.name, hex32(v),
                                  hex32(**f.expected), d.config_key, f.key));
      }
      if (f.eds && *f.eds != v) {
        const bool minor_only = f.sub == 3 && (*f.eds >> 16) == (v >> 16);
        const auto text = fmt::format("device {} {}, the EDS {} says {} ({})", f.name, hex32(v),
                                      f.eds_key, hex32(*f.eds), file);
        if (minor_only) {
          append(notes, text + ": minor revision only");
        } else {
          append(wrong, text);
        }
      }
    }
    const bool any_expected = id.vendor_id || id.product_code || id.revision || id.serial_number;
    const bool eds_identity = eds && (eds->vendor_number() || eds->product_number());
    std::string detail = wrong;
    if (wrong.empty()) {
      detail = seen + (any_expected && eds_identity ? " (as configured and as the EDS says)"
                       : any_expected               ? " (as configured)"
                       : eds_identity               ? " (as the EDS says)"
                                                    : " (nothing expected)");
    }
    if (!notes.empty()) detail += "; " + notes;
    add(device_label(d), "identity", wrong.empty(), detail);
  }

  void object_row(const BenchCanopenDevice& d, canopen::SdoClient& sdo,
                  const canopen::UsedObject& u) {
    const auto label = device_label(d);
    const auto item = canopen::describe(u);
    std::error_code ec;
    const auto bytes = sdo.upload(u.index, u.sub, ec);
    const auto type = canopen::data_type_name(u.data_type);
    if (is_abort(ec, SdoAbort::no_object) || is_abort(ec, SdoAbort::no_sub_index)) {
      if (u.optional()) {
        add(label, item, true, std::string("absent (optional): ") + u.without);
      } else {
        add(label, item, false, "missing: " + ec.message());
      }
      return;
    }
    if (is_abort(ec, SdoAbort::write_only)) {
      add(label, item, u.access == canopen::UsedAccess::kWrite,
          u.access == canopen::UsedAccess::kWrite ? "present, write-only"
                                                  : "write-only: the bench reads it");
      return;
    }
    if (ec) {
      add(label, item, false, "SDO upload failed: " + ec.message());
      return;
    }
    const auto size = canopen::data_type_size(u.data_type);
    const auto alt = canopen::data_type_size(u.alt_data_type);
    if (size != 0 && bytes.size() != size && (alt == 0 || bytes.size() != alt)) {
      add(label, item, false,
          fmt::format("{} bytes read, expected {} ({})", bytes.size(), size, type));
      return;
    }
    std::string access = u.access == canopen::UsedAccess::kRead
                             ? "read"
                             : "read (written by the bench; not written here)";
    if (d.expect->eds) {
      if (const auto* o = d.expect->eds->find(u.index, u.sub)) {
        access += fmt::format(", EDS {}{}", canopen::to_string(o->access),
                              o->pdo_mapping ? ", PDO-mappable" : "");
        if (u.may_be_read_only && !canopen::writable(o->access))
          access += " (may be read-only: the mapping is read back and used as found)";
      }
    }
    add(label, item, true, fmt::format("{}, {} bytes {}", type, bytes.size(), access));
  }

  void brake_row() {
    const auto where = modbus::to_string(config_.brake.link.endpoint);
    const auto label = "brake controller (" + where + ")";
    if (bench_.state() != BenchLifecycle::kUnconfigured) {
      // Connected: the supervisor reads the registers all along (one link per line).
      const auto readback = bench_.brake_readback();
      if (readback) {
        add(label, "registers readable", true,
            fmt::format("supervisor readback: coil {:.3f} A, torque {:.2f} N*m, {:.1f} degC{}",
                        readback->coil_current_a, readback->torque_nm, readback->temperature_c,
                        readback->alarm_text.empty() ? "" : ", " + readback->alarm_text));
      } else {
        add(label, "registers readable", false, "no fresh readback from the supervisor");
      }
      return;
    }
    try {
      modbus::BrakeClient client(config_.brake);
      client.connect();
      const auto r = client.read();
      const auto control = client.read_control();
      client.disconnect();
      add(label, "registers readable", true,
          fmt::format("control 0x{:04X}, coil {:.3f} A, torque {:.2f} N*m, {:.1f} degC{}", control,
                      r.coil_current_a, r.torque_nm, r.temperature_c,
                      r.alarm_text.empty() ? "" : ", " + r.alarm_text));
    } catch (const std::exception& e) {
      add(label, "registers readable", false, e.what());
    }
  }

  // Empty when the bench is connected (acquiring) for the remaining rows.
  std::string connect_if_asked() {
    if (bench_.state() != BenchLifecycle::kUnconfigured) return {};
    if (!options_.connect) return "the bench is not connected";
    try {
      bench_.connect();
      return {};
    } catch (const std::exception& e) {
      return std::string("the bench did not connect: ") + e.what();
    }
  }

  void pdo_row(const BenchCanopenDevice& d, bool answering) {
    const auto label = device_label(d);
    if (!answering) {
      add(label, "PDO mapping", false, "not checked: the node does not answer");
      return;
    }
    auto& sdo = bench_.master().sdo(d.node);
    std::string seen;
    std::string wrong;
    // The connected bench's device knows its TPDOs as used: as found where they are fixed.
    const auto* used = connected_device(d.node);
    const auto tpdos = used ? used->tpdos() : d.tpdos;
    const auto fixed = used ? used->adopted_tpdos().summary() : std::string();
    const auto adopted = used ? used->adopted_tpdos().pdos() : std::vector<canopen::PdoAdoption>{};
    for (std::size_t i = 0; i < tpdos.size(); ++i) {
      const auto& pdo = tpdos[i];
      const unsigned number = i < adopted.size() ? adopted[i].number : static_cast<unsigned>(i + 1);
      const auto map = static_cast<std::uint16_t>(0x1A00 + number - 1);
      std::error_code ec;
      const auto count = sdo.read<std::uint8_t>(map, 0, ec);
      std::string entries;
      bool same = !ec && count == pdo.entries.size();
      for (std::uint8_t k = 1; !ec && k <= count && k <= 8; ++k) {
        const auto e = canopen::PdoEntry::decode(sdo.read<std::uint32_t>(map, k, ec));
        if (ec) break;
        entries +=
            fmt::format("{}0x{:04X}:{}/{}", entries.empty() ? "" : ", ", e.index, e.sub, e.bits);
        if (k > pdo.entries.size() || pdo.entries[k - 1].encode() != e.encode()) same = false;
      }
      if (ec) {
        wrong += fmt::format("TPDO{} mapping unreadable: {}; ", number, ec.message());
        continue;
      }
      seen += fmt::format("{}TPDO{} [{}]", seen.empty() ? "" : ", ", number, entries);
      if (!same)
        wrong += fmt::format("TPDO{} reads back [{}], not the bench's mapping; ", number, entries);
    }
    add(label, "PDO mapping", wrong.empty(),
        wrong.empty() ? (fixed.empty() ? seen : fixed) + " (read back)" : wrong);
  }

  // The bench's own (configured) device on `node`; null when it has none there.
  const CanopenDevice* connected_device(std::uint8_t node) const {
    for (const auto* device : bench_.devices()) {
      const auto* c = dynamic_cast<const CanopenDevice*>(device);
      if (c && c->node() == node) return c;
    }
    return nullptr;
  }

  void observe(const std::vector<BenchCanopenDevice>& devices) {
    const double producer = config_.can.heartbeat_producer_s;
    const double period = config_.description.sync_period_s;
    const double window =
        options_.observe_s > 0 ? options_.observe_s : std::max(3 * producer + 0.05, 100 * period);
    std::map<std::uint8_t, unsigned> heartbeats;
    std::map<std::uint8_t, canopen::NmtState> states;
    std::map<std::uint32_t, unsigned> tpdos;
    double bits = 0;
    auto subscription = bench_.master().bus().on_frame([&](const can::Frame& f) {
      bits += (47.0 + 8.0 * f.len) * 1.2;  // as the bench's estimate: stuffing allowance
      if (const auto hb = canopen::decode_heartbeat(f)) {
        ++heartbeats[hb->node];
        states[hb->node] = hb->state;
      } else {
        ++tpdos[f.id];
      }
    });
    const auto before = bench_.acquisition_stats();
    const auto guards_before = guard_counts();
    const auto t0 = std::chrono::steady_clock::now();
    bench_.idle_for(window);
    // Node guarding runs on the wall clock: a few guard times of it, however fast bench time.
    const double guard_wall =
        bench_.node_guards().empty() ? 0 : 2.5 * config_.can.node_guarding.guard_time_s;
    while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() <
           guard_wall)
      bench_.idle_for(10 * period);
    const auto real = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto after = bench_.acquisition_stats();
    subscription.reset();

    const auto guards_after = guard_counts();
    for (const auto& d : devices) {
      if (const auto* g = bench_.node_guards().guard(d.node)) {
        guard_row(d, *g, guards_after.at(d.node) - guards_before.at(d.node), real);
        continue;
      }
      const auto n = heartbeats[d.node];
      const bool ok = n > 0 && states[d.node] == canopen::NmtState::operational;
      add(device_label(d), "heartbeat", ok,
          n == 0 ? fmt::format("none in {:.2f} s (0x1017 = {} ms)", window,
                               std::lround(producer * 1e3))
                 : fmt::format("{} in {:.2f} s, {}", n, window,
                               std::string(canopen::to_string(states[d.node]))));
    }

    const auto syncs = after.syncs_sent - before.syncs_sent;
    const auto samples = after.samples - before.samples;
    const auto incomplete = after.incomplete_samples - before.incomplete_samples;
    std::string missing;
    struct Expected {
      std::string name;
      std::uint32_t cob;
    };
    // Each TPDO as the devices use it (a fixed mapping may have other PDOs or COB-IDs).
    std::vector<Expected> expected;
    for (const auto& d : devices) {
      const auto* used = connected_device(d.node);
      if (!used) continue;
      const auto& adopted = used->adopted_tpdos().pdos();
      const auto configs = used->tpdos();
      for (std::size_t i = 0; i < configs.size(); ++i) {
        expected.push_back(
            {fmt::format("{} TPDO{}", d.name, i < adopted.size() ? adopted[i].number : i + 1),
             configs[i].cob_id & can::kStandardIdMask});
      }
    }
    for (const auto& e : expected) {
      if (tpdos[e.cob] == 0)
        missing += fmt::format("{}{} (0x{:03X})", missing.empty() ? "" : ", ", e.name, e.cob);
    }
    // The first and the last cycle of the window may be cut by it.
    const bool ok = syncs > 0 && missing.empty() && incomplete <= 2 && samples + 2 >= syncs;
    std::string slow;
    if (after.cycles_waited_for_devices > before.cycles_waited_for_devices) {
      std::string names;
      for (const auto& n : after.late_devices) names += (names.empty() ? "" : ", ") + n;
      slow = fmt::format(
          "; slower than the SYNC rate: {} SYNCs waited past can.cycle_timeout for {} (longest "
          "{:.0f} ms)",
          after.cycles_waited_for_devices - before.cycles_waited_for_devices, names,
          after.longest_device_wait_s * 1e3);
    }
    add("bus", "SYNC round trip", ok,
        (missing.empty()
             ? fmt::format("{} SYNCs, {} samples, {} incomplete; answered by drive TPDO1/TPDO2, "
                           "encoder TPDO1, torque sensor TPDO1",
                           syncs, samples, incomplete)
             : fmt::format("{} SYNCs, no answer from {}", syncs, missing)) +
            slow);

    std::string load =
        fmt::format("estimated {:.1f} % of {:.0f} kbit/s at a {} us SYNC", after.bus_load * 100,
                    config_.can.bitrate / 1e3, std::lround(period * 1e6));
    if (!config_.description.simulated_clock && real > 0)
      load += fmt::format(", received {:.1f} %", bits / real / config_.can.bitrate * 100);
    const bool load_ok = after.bus_load <= config_.can.bus_load_warning;
    add("bus", "bus load", load_ok,
        load_ok ? load
                : load + fmt::format(": above can.bus_load_warning = {:.0f} %",
                                     config_.can.bus_load_warning * 100));
  }

  struct GuardCounts {
    std::uint64_t answers = 0;
    std::uint64_t toggle_errors = 0;
    GuardCounts operator-(const GuardCounts& o) const {
      return {answers - o.answers, toggle_errors - o.toggle_errors};
    }
  };
  std::map<std::uint8_t, GuardCounts> guard_counts() const {
    std::map<std::uint8_t, GuardCounts> out;
    for (const auto* g : bench_.node_guards().all())
      out[g->node()] = {g->answers(), g->toggle_errors()};
    return out;
  }

  // A node without a heartbeat producer: its node-guarding answers in the window.
  void guard_row(const BenchCanopenDevice& d, const canopen::NodeGuard& g, GuardCounts seen,
                 double window) {
    const bool ok =
        seen.answers > 0 && seen.toggle_errors == 0 && g.state() == canopen::NmtState::operational;
    std::string detail =
        seen.answers == 0
            ? fmt::format("no answer in {:.2f} s", window)
            : fmt::format("{} answers in {:.2f} s, {}", seen.answers, window,
                          g.state() ? std::string(canopen::to_string(*g.state())) : "no state");
    if (seen.toggle_errors > 0) detail += fmt::format(", {} toggle errors", seen.toggle_errors);
    detail += fmt::format(" (guard time {} ms, life time {} ms; no heartbeat producer)",
                          g.guard_time().count(), g.life_time().count());
    add(device_label(d), "node guarding", ok, detail);
  }

  void units_row(const BenchCanopenDevice& drive, bool answering) {
    std::string text = fmt::format("drive.counts_per_revolution = {} counts per input turn",
                                   config_.drive.counts_per_revolution);
    if (answering) {
      auto& sdo = bench_.master().sdo(drive.node);
      std::error_code ec;
      const auto increments = sdo.read<std::uint32_t>(0x608F, 1, ec);
      std::error_code ec2;
      const auto revolutions = sdo.read<std::uint32_t>(0x608F, 2, ec2);
      if (!ec && !ec2) {
        text += fmt::format("; drive 0x608F: {} increments per {} motor revolution(s)", increments,
                            revolutions);
      } else {
        text += "; 0x608F not readable";
      }
    }
    const auto& d = config_.drive;
    text += fmt::format(
        "; drive.position_unit = {}, drive.velocity_unit = {}, "
        "drive.acceleration_unit = {}",
        d.position_unit.text, d.velocity_unit.text, d.acceleration_unit.text);
    bool ok = true;
    if (answering) {
      // Issue #20: what the drive states of its units, against the config's.
      const auto statement = compare_drive_unit_statement(
          read_drive_unit_statement(bench_.master().sdo(drive.node)), d);
      ok = statement.agree;
      text += "; " + statement.detail;
      if (!statement.stated) ok = units_by_motion(text);
    }
    add(device_label(drive), "units", ok, text);
  }

  // The drive does not state its units: compare them with the encoders by a bounded motion,
  // when asked and the bench is connected and inactive. False only when the motion shows them
  // wrong or could not tell.
  bool units_by_motion(std::string& text) {
    if (!options_.motion) {
      text += " (not compared by motion: wavebench bench check without --no-motion does)";
      return true;
    }
    if (bench_.state() != BenchLifecycle::kInactive) {
      text += fmt::format("; not compared by motion: the bench is {}, not inactive",
                          lifecycle_name(bench_.state()));
      return false;
    }
    const auto moved = check_units_by_motion(bench_, config_.drive);
    text += "; " + moved.detail;
    return moved.ok;
  }

  CanopenBench& bench_;
  const BenchConfig& config_;
  CheckOptions options_;
  CheckReport report_;
};

}  // namespace

bool CheckReport::all_green() const {
  return !rows.empty() &&
         std::all_of(rows.begin(), rows.end(), [](const CheckRow& r) { return r.ok; });
}

CheckReport check_bench(CanopenBench& bench, const CheckOptions& options) {
  return Check(bench, options).run();
}

std::string format_check_table(const CheckReport& report) {
  std::size_t device_width = 6;
  std::size_t item_width = 4;
  for (const auto& r : report.rows) {
    device_width = std::max(device_width, r.device.size());
    item_width = std::max(item_width, r.item.size());
  }
  std::string out = fmt::format("{:<5}  {:<{}}  {:<{}}  {}\n", "", "device", device_width, "item",
                                item_width, "detail");
  std::size_t red = 0;
  for (const auto& r : report.rows) {
    if (!r.ok) ++red;
    out += fmt::format("{:<5}  {:<{}}  {:<{}}  {}\n", r.ok ? "ok" : "RED", r.device, device_width,
                       r.item, item_width, r.detail);
  }
  out +=
      red == 0
          ? fmt::format("bench '{}': all {} checks green\n", report.bench, report.rows.size())
          : fmt::format("bench '{}': {} of {} checks red\n", report.bench, red, report.rows.size());
  return out;
}

nlohmann::json check_report_json(const CheckReport& report) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& r : report.rows) {
    rows.push_back({{"device", r.device}, {"item", r.item}, {"ok", r.ok}, {"detail", r.detail}});
  }
  return {{"bench", report.bench}, {"all_green", report.all_green()}, {"rows", rows}};
}

}  // namespace wavebench::bench
