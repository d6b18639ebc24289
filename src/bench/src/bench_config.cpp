#include "wavebench/bench/bench_config.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>

#include "wavebench/config/config_error.hpp"
#include "wavebench/config/config_text.hpp"
#include "wavebench/config/shipped_configs.hpp"
#include "wavebench/config/twin_case.hpp"
#include "wavebench/config/units.hpp"
#include "wavebench/simdevices/simulated_bench_config.hpp"
#include "wavebench/storage/sync_sample.hpp"
#include "wavebench/strict_yaml/yaml_section.hpp"

namespace wavebench::bench {
namespace {

using config::ConfigError;
using config::Dimension;
using strict_yaml::set_if;
using strict_yaml::YamlSection;

// Names and serials go into run folders, the runs index and report titles: one short line.
void read_label(YamlSection& s, const char* key, std::string& out) {
  if (const auto v = s.optional_label(key)) out = *v;
}

// A sign of +1 or -1 (a direction, a channel's sense).
void read_sign(YamlSection& s, const char* key, int& out, const char* expected) {
  const auto v = s.optional_integer(key, -1, 1);
  if (v && *v == 0) s.fail(key, "0", expected);
  set_if(v, out);
}

std::filesystem::path resolve(const std::filesystem::path& base, const std::string& p) {
  std::filesystem::path path(p);
  return path.is_absolute() ? path : (base / path).lexically_normal();
}

// "0x6130:1" -> index, sub. Hand-written: the CiA 306 notation has no parser here.
void read_object(YamlSection& s, std::uint16_t& index, std::uint8_t& sub) {
  const auto value = s.optional_text("object");
  if (!value) return;
  const auto colon = value->find(':');
  try {
    std::size_t used = 0;
    const unsigned long i = std::stoul(value->substr(0, colon), &used, 0);
    if (used != (colon == std::string::npos ? value->size() : colon) || i > 0xFFFF)
      throw std::invalid_argument(*value);
    unsigned long sb = 0;
    if (colon != std::string::npos) {
      sb = std::stoul(value->substr(colon + 1), &used, 0);
      if (used != value->size() - colon - 1 || sb > 0xFF) throw std::invalid_argument(*value);
    }
    index = static_cast<std::uint16_t>(i);
    sub = static_cast<std::uint8_t>(sb);
  } catch (const std::exception&) {
    s.fail("object", *value, "an object as INDEX:SUB, e.g. \"0x6130:1\"");
  }
}

void read_value_type(YamlSection& s, canopen::ValueType& out) {
  const auto t = s.optional_text("type");
  if (!t) return;
  const auto type = canopen::parse_value_type(*t);
  if (!type) s.fail("type", *t, "u8, u16, u32, i8, i16, i32, f32 or f64");
  out = *type;
}

void read_top(YamlSection& root, BenchConfig& c, const std::filesystem::path& base) {
  auto& d = c.description;
  read_label(root, "name", d.name);
  read_label(root, "unit_serial", d.unit_serial);
  if (const auto v = root.optional_quantity("rated_torque", Dimension::kTorque)) {
    if (*v <= 0) root.fail("rated_torque", root.value_text("rated_torque"), "a torque > 0");
    d.rated_torque_nm = *v;
  }
  if (auto g = root.optional_section("gear")) {
    set_if(g->optional_number("ratio", 1e-3, 1e6), d.sense.ratio);
    read_sign(*g, "direction_sign", d.sense.direction_sign, "+1 or -1");
    g->finish();
  }
  if (const auto v = root.optional_quantity_in("sync_period", Dimension::kTime, 1e-4, 1.0,
                                               "a period between 100 us and 1 s")) {
    if (std::abs(std::round(*v * 1e6) - *v * 1e6) > 1e-6)
      root.fail("sync_period", root.value_text("sync_period"), "a whole number of microseconds");
    d.sync_period_s = *v;
  }
  if (const auto v = root.optional_choice("clock", {"real", "simulated"})) {
    c.clock = *v == "real" ? BenchClockKind::kReal : BenchClockKind::kSimulated;
  }
  if (const auto v = root.optional_text("twin_case")) d.twin_case_path = resolve(base, *v).string();
}

void read_can(YamlSection& s, CanSettings& can) {
  if (const auto v = s.optional_text("interface")) {
    if (v->empty()) s.fail("interface", "", "inproc or an interface name");
    can.interface = *v;
  }
  // Classic CAN ends at 1 Mbit/s, CAN FD's data phase near 8: 10 Mbit/s leaves room.
  set_if(s.optional_number("bitrate", 1e4, 1e7), can.bitrate);
  // An SDO answer later than 60 s is a dead node, not a slow one.
  set_if(s.optional_quantity_in("sdo_timeout", Dimension::kTime, strict_yaml::kAboveZero, 60,
                                "a time in (0, 60 s]"),
         can.sdo_timeout_s);
  // 0x1017 is a UNSIGNED16 of milliseconds.
  set_if(s.optional_quantity_in("heartbeat_producer", Dimension::kTime, 1e-3, 65.535,
                                "a time in [1 ms, 65.535 s]"),
         can.heartbeat_producer_s);
  // A fraction of the bit rate: above 1 the warning could never come.
  set_if(
      s.optional_quantity_in("bus_load_warning", Dimension::kDimensionless, strict_yaml::kAboveZero,
                             1, "a fraction of the bit rate in (0, 1], e.g. 0.8 or \"80 %\""),
      can.bus_load_warning);
  // Real time to wait for one cycle's PDOs on the simulated clock: beyond 10 s a cycle is lost.
  set_if(s.optional_quantity_in("cycle_timeout", Dimension::kTime, strict_yaml::kAboveZero, 10,
                                "a time in (0, 10 s]"),
         can.cycle_timeout_s);
  // Bench time for the drive to show a quick stop: a drive slower than 10 s is stopped by NMT.
  set_if(s.optional_quantity_in("quick_stop_timeout", Dimension::kTime, strict_yaml::kAboveZero, 10,
                                "a time in (0, 10 s]"),
         can.quick_stop_timeout_s);
  if (auto g = s.optional_section("node_guarding")) {
    set_if(g->optional_quantity_in("guard_time", Dimension::kTime, 1e-3, 65.535,
                                   "a time in [1 ms, 65.535 s]"),
           can.node_guarding.guard_time_s);
    set_if(g->optional_integer("life_time_factor", 1, 255), can.node_guarding.life_time_factor);
    if (const auto nodes = g->optional_integer_list("nodes", 1, 127)) {
      can.node_guarding.nodes.clear();
      for (const auto n : *nodes) can.node_guarding.nodes.push_back(static_cast<std::uint8_t>(n));
    }
    g->finish();
  }
  if (auto nodes = s.optional_section("nodes")) {
    set_if(nodes->optional_integer("drive", 1, 127), can.drive_node);
    set_if(nodes->optional_integer("encoder", 1, 127), can.encoder_node);
    set_if(nodes->optional_integer("torque_sensor", 1, 127), can.torque_node);
    nodes->finish();
  }
  s.finish();
  if (can.drive_node == can.encoder_node || can.drive_node == can.torque_node ||
      can.encoder_node == can.torque_node) {
    s.fail("nodes",
           std::to_string(can.drive_node) + ", " + std::to_string(can.encoder_node) + ", " +
               std::to_string(can.torque_node),
           "three different node ids");
  }
}

// `eds:` and `identity:` of a CANopen device section.
void read_expectations(YamlSection& s, const std::filesystem::path& base, NodeExpectations& e) {
  if (const auto v = s.optional_text("eds")) {
    const auto path = resolve(base, *v);
    try {
      e.eds = std::make_shared<const canopen::Eds>(canopen::Eds::load(path));
    } catch (const canopen::EdsError& error) {
      s.fail("eds", path.string(), std::string("a CiA 306 EDS: ") + error.what());
    }
    e.eds_path = path;
  }
  if (auto id = s.optional_section("identity")) {
    set_if(id->optional_integer("vendor_id", 0, 0xFFFFFFFFLL), e.identity.vendor_id);
    set_if(id->optional_integer("product_code", 0, 0xFFFFFFFFLL), e.identity.product_code);
    set_if(id->optional_integer("revision", 0, 0xFFFFFFFFLL), e.identity.revision);
    set_if(id->optional_integer("serial_number", 0, 0xFFFFFFFFLL), e.identity.serial_number);
    id->finish();
  }
}

// Where the config is silent, values from the devices' EDS files: the torque sensor's data type
// (the DataType of its object). The encoder's resolution and turns stay read from the device
// (0x6501/0x6502), which knows its own configuration better than a data sheet's defaults.
void apply_eds_defaults(bool torque_type_given, BenchConfig& c) {
  auto& sensor = c.torque_sensor.sensor;
  if (!torque_type_given && c.torque_sensor.expect.eds) {
    if (const auto* o = c.torque_sensor.expect.eds->find(sensor.index, sensor.sub)) {
      for (auto t : {canopen::ValueType::u8, canopen::ValueType::u16, canopen::ValueType::u32,
                     canopen::ValueType::u64, canopen::ValueType::i8, canopen::ValueType::i16,
                     canopen::ValueType::i32, canopen::ValueType::i64, canopen::ValueType::f32,
                     canopen::ValueType::f64}) {
        if (canopen::data_type_of(t) == o->data_type) sensor.type = t;
      }
    }
  }
}

void read_drive_units(YamlSection& s, DriveSettings& d) {
  const auto unit = [&](const char* key, DriveQuantity q, DriveUnitChoice& out) {
    const auto t = s.optional_text(key);
    if (!t) return;
    try {
      out = parse_drive_unit(*t, q);
    } catch (const std::invalid_argument& e) {
      s.fail(key, *t, e.what());
    }
  };
  unit("position_unit", DriveQuantity::kPosition, d.position_unit);
  unit("velocity_unit", DriveQuantity::kVelocity, d.velocity_unit);
  unit("acceleration_unit", DriveQuantity::kAcceleration, d.acceleration_unit);
  if (const auto t = s.optional_text("torque_actual_scale")) {
    if (*t == "rated") {
      d.torque_actual_nm_per_unit.reset();
      return;
    }
    const std::string expected =
        "rated (per mille of the drive's rated torque 0x6076) or a torque > 0 per unit of 0x6077 "
        "(\"0.001 N*m\")";
    double scale = 0;
    try {
      scale = strict_yaml::parse_quantity(*t, Dimension::kTorque, "");
    } catch (const ConfigError&) {
      s.fail("torque_actual_scale", *t, expected);
    }
    if (!(scale > 0)) s.fail("torque_actual_scale", *t, expected);
    d.torque_actual_nm_per_unit = scale;
  }
}

bool iso_date(const std::string& v) {
  const auto digit = [&](std::size_t i) { return v[i] >= '0' && v[i] <= '9'; };
  if (v.size() != 10 || v[4] != '-' || v[7] != '-') return false;
  for (const std::size_t i : {0, 1, 2, 3, 5, 6, 8, 9})
    if (!digit(i)) return false;
  const int month = std::stoi(v.substr(5, 2)), day = std::stoi(v.substr(8, 2));
  return month >= 1 && month <= 12 && day >= 1 && day <= 31;
}

// The optional `calibration: {id, due}` of a measuring device, for certificates.
SensorCalibration read_calibration(YamlSection& device, const char* sensor) {
  SensorCalibration cal;
  cal.sensor = sensor;
  auto s = device.optional_section("calibration");
  if (!s) return cal;
  if (!s->has("id")) s->fail("id", "", "a calibration certificate number (the key is required)");
  cal.id = *s->optional_label("id", 64);
  cal.due = s->text("due");
  if (!iso_date(cal.due)) s->fail("due", cal.due, "a date YYYY-MM-DD (the next calibration)");
  s->finish();
  return cal;
}

void read_devices(YamlSection& root, BenchConfig& c, const std::filesystem::path& base) {
  auto& sensors = c.description.sensors;
  sensors = {
      {"input encoder (drive)", {}, {}}, {"output encoder", {}, {}}, {"torque sensor", {}, {}}};
  if (auto s = root.optional_section("drive")) {
    sensors[0] = read_calibration(*s, "input encoder (drive)");
    read_expectations(*s, base, c.drive.expect);
    set_if(s->optional_integer("counts_per_revolution", 1, 1LL << 31),
           c.drive.counts_per_revolution);
    set_if(s->optional_number("profile_acceleration", 0, 1e9), c.drive.profile_acceleration_rad_s2);
    set_if(s->optional_quantity_in("target_settle", Dimension::kTime, 0, 60, "a time in [0, 60 s]"),
           c.drive.target_settle_s);
    read_drive_units(*s, c.drive);
    s->finish();
  }
  if (auto s = root.optional_section("encoder")) {
    sensors[1] = read_calibration(*s, "output encoder");
    read_expectations(*s, base, c.encoder.expect);
    set_if(s->optional_integer("counts_per_turn", 2, 1LL << 31), c.encoder.counts_per_turn);
    set_if(s->optional_integer("turns", 1, 1LL << 20), c.encoder.turns);
    set_if(s->optional_quantity_in("noise", Dimension::kAngle, 0, M_PI / 180,
                                   "an angle in [0, 1 deg]"),
           c.encoder.noise_rad);
    s->finish();
  }
  bool torque_type_given = false;
  if (auto s = root.optional_section("torque_sensor")) {
    sensors[2] = read_calibration(*s, "torque sensor");
    read_expectations(*s, base, c.torque_sensor.expect);
    auto& sensor = c.torque_sensor.sensor;
    read_object(*s, sensor.index, sensor.sub);
    torque_type_given = s->has("type");
    read_value_type(*s, sensor.type);
    if (const auto v = s->optional_number("scale", -1e9, 1e9)) {
      if (*v == 0) s->fail("scale", s->value_text("scale"), "a non-zero N*m per raw unit");
      sensor.scale = *v;
    }
    set_if(s->optional_quantity_in("offset", Dimension::kTorque, -1e6, 1e6,
                                   "a torque in [-1e6, 1e6] N*m"),
           sensor.offset);
    set_if(s->optional_quantity_in("noise", Dimension::kTorque, 0, 1e4, "a torque in [0, 1e4] N*m"),
           c.torque_sensor.noise_nm);
    s->finish();
  }
  apply_eds_defaults(torque_type_given, c);
}

// One `devices:` entry: {kind, node, sign, the kind's keys}; keys another kind has are refused.
ChannelDeviceSettings read_channel_device(YamlSection& v, const std::string& channel,
                                          std::set<int>& nodes) {
  ChannelDeviceSettings d;
  d.channel = channel;
  d.kind = v.text("kind");
  const auto* kind = find_channel_device_kind(d.kind);
  if (!kind) {
    std::string list;
    for (const auto& k : channel_device_kinds()) list += (list.empty() ? "" : ", ") + k.kind;
    v.fail("kind", d.kind, "one of " + list);
  }
  const auto takes = [&](const char* key) {
    return std::find(kind->keys.begin(), kind->keys.end(), key) != kind->keys.end();
  };
  set_if(v.optional_integer("node", 1, 127), d.node);
  if (!v.has("node")) v.fail("node", "", "a node id in [1, 127] (the key is required)");
  if (!nodes.insert(d.node).second)
    v.fail("node", std::to_string(d.node), "a node id no other device of the bench uses");
  read_sign(v, "sign", d.sign, "1 or -1");
  if (takes("counts_per_turn"))
    set_if(v.optional_integer("counts_per_turn", 2, 1LL << 31), d.counts_per_turn);
  if (takes("turns")) set_if(v.optional_integer("turns", 1, 1LL << 20), d.turns);
  if (takes("object")) read_object(v, d.torque.index, d.torque.sub);
  if (takes("type")) read_value_type(v, d.torque.type);
  if (takes("scale")) {
    if (const auto x = v.optional_number("scale", -1e9, 1e9)) {
      if (*x == 0) v.fail("scale", v.value_text("scale"), "a non-zero scale");
      d.torque.scale = *x;
    }
  }
  if (takes("offset")) {
    set_if(v.optional_quantity_in("offset", Dimension::kTorque, -1e6, 1e6,
                                  "a torque in [-1e6, 1e6] N*m"),
           d.torque.offset);
  }
  v.finish();
  return d;
}

// `devices:`: channel name -> {kind, node, sign, the kind's keys}. Kinds come from the
// registry (device_kind_registry.cpp), so a new kind needs no change here beyond its keys.
void read_channel_devices(YamlSection& root, BenchConfig& c) {
  auto devices = root.optional_section("devices");
  if (!devices) return;
  std::set<int> nodes{c.can.drive_node, c.can.encoder_node, c.can.torque_node};
  const std::vector<std::string> names = devices->keys();
  for (const auto& name : names) {
    try {
      storage::check_extra_channels(std::vector<storage::ChannelInfo>{{name, "rad"}});
    } catch (const std::invalid_argument& e) {
      devices->fail("", name,
                    "a channel name of [a-z0-9_], 1..31 bytes, not a core channel's (" +
                        std::string(e.what()) + ")");
    }
    if (c.devices.size() == storage::kMaxExtraChannels)
      devices->fail("", std::to_string(names.size()) + " devices",
                    "at most " + std::to_string(storage::kMaxExtraChannels));
    YamlSection v = devices->section(name);
    c.devices.push_back(read_channel_device(v, name, nodes));
  }
  devices->finish();
}

// A safety limit, bounded above as well as below: a limit nothing reaches is a limit switched
// off (a heartbeat_timeout of 1e9 s was), and it is refused as such.
struct SafetyKey {
  const char* key;
  Dimension dimension;
  double most;           // SI
  const char* expected;  // the range as written, and why it ends there
  double SafetyLimits::*field;
};

constexpr SafetyKey kSafetyKeys[] = {
    {"max_input_speed", Dimension::kAngularSpeed, 1e4,
     "a speed in (0, 1e4 rad/s] (about 95 000 rpm: no gear input turns faster)",
     &SafetyLimits::max_input_speed_rad_s},
    {"max_brake_current", Dimension::kCurrent, 1000,
     "a current in (0, 1000 A] (brake.limits.max_current_a ends there too)",
     &SafetyLimits::max_brake_current_a},
    {"max_brake_torque", Dimension::kTorque, 1e6,
     "a torque in (0, 1e6 N*m] (brake.limits.max_torque_nm ends there too)",
     &SafetyLimits::max_brake_torque_nm},
    {"max_measured_torque", Dimension::kTorque, 1e6,
     "a torque in (0, 1e6 N*m] (beyond every strain-wave gear and torque sensor)",
     &SafetyLimits::max_measured_torque_nm},
    {"max_following_error", Dimension::kAngle, 100 * 2 * M_PI,
     "an angle in (0, 100 rev] of the input (a drive 100 turns behind has lost its load)",
     &SafetyLimits::max_following_error_rad},
    {"max_coil_temperature", Dimension::kTemperature, 250,
     "a temperature in (0, 250 degC] (class H insulation ends at 180 degC)",
     &SafetyLimits::max_coil_temperature_c},
    {"max_te_excursion", Dimension::kAngle, M_PI,
     "an angle in (0, 0.5 rev] (an error of half an output turn is no transmission error)",
     &SafetyLimits::max_te_excursion_rad},
    {"heartbeat_timeout", Dimension::kTime, 10,
     "a time in (0, 10 s] (a node silent for longer is lost: the check would be off in effect)",
     &SafetyLimits::heartbeat_timeout_s},
    {"modbus_link_timeout", Dimension::kTime, 60,
     "a time in (0, 60 s] (brake.timeouts.link_loss_ms ends there too)",
     &SafetyLimits::modbus_link_timeout_s},
};

void read_safety(YamlSection& s, SafetyLimits& l) {
  // An absent key switches its limit off; a written one must be a limit. A negative or zero
  // value used to mean "off" too, so a sign typo silently disarmed the bench.
  for (const auto& k : kSafetyKeys) {
    const auto v = s.optional_quantity(k.key, k.dimension);
    if (!v) continue;
    if (!(*v > 0)) {
      s.fail(k.key, s.value_text(k.key),
             std::string(k.expected) + "; leave the key out to switch this limit off");
    }
    if (*v > k.most) s.fail(k.key, s.value_text(k.key), k.expected);
    l.*k.field = *v;
  }
  s.finish();
}

void read_true_gear(YamlSection& g, SimulatedSettings& s, const std::filesystem::path& base) {
  if (const auto v = g.optional_text("case")) s.true_gear_case = resolve(base, *v);
  set_if(g.optional_number("te_amplitude_scale", 0, 100), s.variation.te_amplitude_scale);
  set_if(g.optional_quantity_in("te_phase_shift", Dimension::kAngle, -2 * M_PI, 2 * M_PI,
                                "an angle in [-1 rev, 1 rev]"),
         s.variation.te_phase_shift_rad);
  set_if(g.optional_number("stiffness_scale", 1e-3, 1e3), s.variation.stiffness_scale);
  if (const auto v = g.optional_quantity_in("backlash", Dimension::kAngle, 0, M_PI / 180,
                                            "an angle in [0, 1 deg]")) {
    s.variation.backlash_rad = *v;
  }
  g.finish();
}

// `simulated:`, or nothing for an in-process bench without one (all defaults).
void read_simulated(YamlSection* n, BenchConfig& c, const std::filesystem::path& base) {
  SimulatedSettings s;
  s.true_gear_case = config::shipped_config_dir() / "twin" / "bench-unit-seed004.yaml";
  if (n) {
    if (auto g = n->optional_section("true_gear")) read_true_gear(*g, s, base);
    if (const auto v = n->optional_choice("brake_server", {"true", "false"})) {
      s.brake_server = *v == "true";
    }
    if (auto sb = n->optional_section("simbench")) {
      // A simulated device sits at can.nodes unless simbench names its node_id (read from a
      // copy, so the reader below still sees the keys unread).
      const auto names_node = [&](const char* device) {
        YamlSection look = *sb;
        const auto d = look.has_section(device) ? look.optional_section(device) : std::nullopt;
        return d && d->has("node_id");
      };
      const bool drive = names_node("drive"), encoder = names_node("encoder"),
                 torque = names_node("torque_sensor");
      s.devices = std::make_shared<const simdevices::SimulatedBenchConfig>(
          simdevices::read_simulated_bench_section(*sb));
      if (drive) s.drive_node = s.devices->drive.node_id;
      if (encoder) s.encoder_node = s.devices->encoder.node_id;
      if (torque) s.torque_node = s.devices->torque_sensor.node_id;
    }
    n->finish();
  }
  c.simulated = std::move(s);
}

}  // namespace

BenchConfig parse_bench_config(const std::string& yaml_text, const std::filesystem::path& base_dir,
                               const std::string& source) {
  BenchConfig c;
  c.source = source;
  c.text = yaml_text;
  c.description.name = "bench";
  c.description.sense = {100, 1};
  c.description.rated_torque_nm = 100;
  c.description.twin_case_path =
      (config::shipped_config_dir() / "twin" / "bench-unit-seed004.yaml").string();
  c.brake.link.endpoint.port = 1502;
  try {
    YamlSection root = strict_yaml::document_section(config::parse_config_yaml(yaml_text, source),
                                                     source, "a mapping of bench settings");
    read_top(root, c, base_dir);
    if (auto can = root.optional_section("can")) read_can(*can, c.can);
    read_devices(root, c, base_dir);
    read_channel_devices(root, c);
    if (auto brake = root.optional_section("brake")) c.brake = modbus::read_brake_config(*brake);
    if (auto safety = root.optional_section("safety")) read_safety(*safety, c.description.limits);
    if (c.description.limits.modbus_link_timeout_s > 0) {
      c.brake.link.link_loss_timeout =
          std::chrono::milliseconds(std::lround(c.description.limits.modbus_link_timeout_s * 1e3));
    }
    if (auto sim = root.optional_section("simulated")) {
      read_simulated(&*sim, c, base_dir);
    } else if (c.in_process()) {
      read_simulated(nullptr, c, base_dir);
    }
    root.finish();

    auto& d = c.description;
    d.simulated_clock = c.clock == BenchClockKind::kSimulated;
    d.max_brake_torque_nm = c.brake.limits.max_torque_nm;
    if (d.limits.max_brake_torque_nm > 0)
      d.max_brake_torque_nm = std::min(d.max_brake_torque_nm, d.limits.max_brake_torque_nm);
    d.input_encoder_resolution_rad = 2 * M_PI / c.drive.counts_per_revolution;
    d.output_encoder_noise_rad = c.encoder.noise_rad;
    if (c.encoder.counts_per_turn)
      d.output_encoder_resolution_rad = 2 * M_PI / *c.encoder.counts_per_turn;
    d.torque_noise_nm = c.torque_sensor.noise_nm;
    // An integer process value steps by its scale; a float one has no step worth budgeting.
    const auto type = c.torque_sensor.sensor.type;
    if (type != canopen::ValueType::f32 && type != canopen::ValueType::f64) {
      d.torque_resolution_nm = std::abs(c.torque_sensor.sensor.scale);
    }
    try {
      d.twin_gear = config::load_twin_case(d.twin_case_path).gear;
    } catch (const ConfigError& e) {
      throw ConfigError("twin_case", d.twin_case_path, std::string("a twin case: ") + e.what());
    }
    if (std::abs(d.twin_gear.geometry.ratio - d.sense.ratio) > 1e-9 * d.sense.ratio) {
      throw ConfigError("gear.ratio", std::to_string(d.sense.ratio),
                        "the twin case's ratio " + std::to_string(d.twin_gear.geometry.ratio));
    }
  } catch (const ConfigError& e) {
    throw e.with_source(source);
  }
  return c;
}

BenchConfig load_bench_config(const std::filesystem::path& path) {
  return parse_bench_config(config::read_config_text(path), path.parent_path(), path.string());
}

BenchConfig default_simulated_bench_config() {
  return load_bench_config(config::shipped_config_dir() / "benches" / "sim.yaml");
}

BenchConfig bench_config_from_argument(const std::string& sim_or_path) {
  // "sim" is the name of the release before (issue #23): an alias for one more release.
  if (sim_or_path.empty() || sim_or_path == "simulated" || sim_or_path == "sim") {
    return default_simulated_bench_config();
  }
  return load_bench_config(sim_or_path);
}

}  // namespace wavebench::bench
