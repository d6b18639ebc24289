#include "wavebench/simdevices/simulated_bench_config.hpp"

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "wavebench/strict_yaml/strict_yaml.hpp"

namespace wavebench::simdevices {
namespace {

std::string describe(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  return node.IsMap() ? "<map>" : node.IsSequence() ? "<list>" : "<null>";
}

// The message format of every config loader (strict_yaml::RefusedConfig).
[[noreturn]] void bad(const std::string& key, const std::string& value,
                      const std::string& expected) {
  throw std::invalid_argument(
      strict_yaml::RefusedConfig(key, value, expected, "simbench config").what());
}
[[noreturn]] void bad(const std::string& key, const YAML::Node& node, const std::string& expected) {
  bad(key, describe(node), expected);
}

// Unknown keys are refused: a misspelt key would otherwise leave its default in place silently.
void check_keys(const YAML::Node& node, const std::string& section,
                std::initializer_list<const char*> known) {
  if (!node.IsMap()) bad(section, node, "a map");
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    bool found = false;
    std::string list;
    for (const char* k : known) {
      found = found || key == k;
      list += (list.empty() ? "" : ", ") + std::string(k);
    }
    if (!found) bad(section + "." + key, kv.second, "one of the known keys: " + list);
  }
}

template <typename T>
void read_integer(const YAML::Node& parent, const std::string& section, const char* key, T& out,
                  long long lo, long long hi) {
  const YAML::Node n = parent[key];
  if (!n) return;
  const std::string name = section + "." + key;
  long long v = 0;
  try {
    v = n.as<long long>();
  } catch (const YAML::Exception&) {
    bad(name, n, "an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
  }
  if (v < lo || v > hi)
    bad(name, n, "an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
  out = static_cast<T>(v);
}

void read_double(const YAML::Node& parent, const std::string& section, const char* key, double& out,
                 double lo, double hi = std::numeric_limits<double>::max()) {
  const YAML::Node n = parent[key];
  if (!n) return;
  const std::string name = section + "." + key;
  double v = 0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    bad(name, n, "a number >= " + std::to_string(lo));
  }
  if (!(v >= lo && v <= hi))
    bad(name, n, "a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  out = v;
}

// [numerator, denominator] of a factor group object. 0 and values >= 2^31 are taken: they
// model a drive whose factor group a master must refuse.
void read_fraction(const YAML::Node& parent, const std::string& section, const char* key,
                   std::uint32_t& numerator, std::uint32_t& denominator) {
  const YAML::Node n = parent[key];
  if (!n) return;
  const std::string name = section + "." + key;
  const std::string expected = "[numerator, denominator], two integers in 0..4294967295";
  if (!n.IsSequence() || n.size() != 2) bad(name, n, expected);
  long long v[2] = {0, 0};
  for (std::size_t i = 0; i < 2; ++i) {
    try {
      v[i] = n[i].as<long long>();
    } catch (const YAML::Exception&) {
      bad(name, n, expected);
    }
    if (v[i] < 0 || v[i] > 0xFFFFFFFFLL) bad(name, n, expected);
  }
  numerator = static_cast<std::uint32_t>(v[0]);
  denominator = static_cast<std::uint32_t>(v[1]);
}

void read_factor_group(const YAML::Node& n, DriveFactorGroupConfig& f) {
  const std::string s = "simbench.drive.factor_group";
  check_keys(n, s,
             {"position_encoder_resolution", "velocity_encoder_resolution", "gear_ratio",
              "feed_constant"});
  read_fraction(n, s, "position_encoder_resolution", f.position_encoder_increments,
                f.position_encoder_revolutions);
  read_fraction(n, s, "velocity_encoder_resolution", f.velocity_encoder_increments,
                f.velocity_encoder_revolutions);
  read_fraction(n, s, "gear_ratio", f.gear_motor_revolutions, f.gear_shaft_revolutions);
  read_fraction(n, s, "feed_constant", f.feed, f.feed_shaft_revolutions);
}

void read_drive_units(const YAML::Node& n, ServoDriveConfig& d) {
  const std::string s = "simbench.drive";
  if (const YAML::Node u = n["velocity_unit"]) {
    const std::string v = u.IsScalar() ? u.Scalar() : "";
    if (v == "counts/s") {
      d.velocity_unit = DriveVelocityUnit::kCounts;
    } else if (v == "rpm") {
      d.velocity_unit = DriveVelocityUnit::kRpm;
    } else if (v == "0.1 rpm") {
      d.velocity_unit = DriveVelocityUnit::kDeciRpm;
    } else if (v == "factor_group") {
      d.velocity_unit = DriveVelocityUnit::kFactorGroup;
    } else {
      bad(s + ".velocity_unit", u, "counts/s, rpm, 0.1 rpm or factor_group");
    }
  }
  if (const YAML::Node f = n["factor_group"]) read_factor_group(f, d.factor_group);
  if (const YAML::Node a = n["absent_objects"]) {
    const std::string expected = "a list of the optional objects \"0x60F4\", \"0x6077\"";
    if (!a.IsSequence()) bad(s + ".absent_objects", a, expected);
    d.absent_objects.clear();
    for (const auto& item : a) {
      const std::string text = item.IsScalar() ? item.Scalar() : "";
      std::uint16_t index = 0;
      if (text == "0x60F4" || text == "0x60f4") {
        index = 0x60F4;
      } else if (text == "0x6077") {
        index = 0x6077;
      } else {
        bad(s + ".absent_objects", item, expected);
      }
      d.absent_objects.push_back(index);
    }
  }
}

void read_drive(const YAML::Node& n, ServoDriveConfig& d) {
  const std::string s = "simbench.drive";
  check_keys(n, s,
             {"node_id", "counts_per_revolution", "rated_torque_nm", "max_torque_permille",
              "max_motor_speed_rpm", "position_gain", "velocity_gain", "velocity_integral_time_s",
              "control_period_us", "quick_stop_option", "following_error_window",
              "following_error_timeout_ms", "serial_number", "velocity_unit", "factor_group",
              "absent_objects"});
  read_drive_units(n, d);
  read_integer(n, s, "node_id", d.node_id, 1, 127);
  read_integer(n, s, "counts_per_revolution", d.counts_per_revolution, 4, 1LL << 30);
  read_double(n, s, "rated_torque_nm", d.rated_torque_nm, 1e-3, 1e4);
  read_integer(n, s, "max_torque_permille", d.max_torque_permille, 1, 65535);
  read_integer(n, s, "max_motor_speed_rpm", d.max_motor_speed_rpm, 1, 100000);
  read_double(n, s, "position_gain", d.position_gain, 0, 1e6);
  read_double(n, s, "velocity_gain", d.velocity_gain, 0, 1e6);
  read_double(n, s, "velocity_integral_time_s", d.velocity_integral_time, 0, 1e3);
  double period_us = d.control_period * 1e6;
  read_double(n, s, "control_period_us", period_us, 10, 10000);
  d.control_period = period_us * 1e-6;
  read_integer(n, s, "quick_stop_option", d.quick_stop_option, 0, 8);
  read_integer(n, s, "following_error_window", d.following_error_window, 0, 0xFFFFFFFFLL);
  read_integer(n, s, "following_error_timeout_ms", d.following_error_timeout_ms, 0, 65535);
  read_integer(n, s, "serial_number", d.identity.serial_number, 0, 0xFFFFFFFFLL);
}

void read_encoder(const YAML::Node& n, EncoderConfig& e,
                  const std::string& s = "simbench.encoder") {
  check_keys(n, s,
             {"node_id", "resolution", "revolutions", "noise_arcsec", "seed", "serial_number"});
  read_integer(n, s, "node_id", e.node_id, 1, 127);
  read_integer(n, s, "resolution", e.single_turn_resolution, 2, 1LL << 31);
  read_integer(n, s, "revolutions", e.revolutions, 1, 65535);
  double arcsec = e.noise_rad * 180 * 3600 / std::numbers::pi;
  read_double(n, s, "noise_arcsec", arcsec, 0, 3600);
  e.noise_rad = arcsec * std::numbers::pi / (180 * 3600);
  read_integer(n, s, "seed", e.seed, 0, std::numeric_limits<long long>::max());
  read_integer(n, s, "serial_number", e.identity.serial_number, 0, 0xFFFFFFFFLL);
}

void read_torque_sensor(const YAML::Node& n, TorqueSensorConfig& t) {
  const std::string s = "simbench.torque_sensor";
  check_keys(n, s, {"node_id", "object", "type", "scale", "noise_nm", "offset_nm", "seed"});
  read_integer(n, s, "node_id", t.node_id, 1, 127);
  if (const YAML::Node o = n["object"]) {
    // "0x6130:1" or "0x6130" (sub-index 0)
    const std::string text = o.IsScalar() ? o.Scalar() : "";
    try {
      std::size_t used = 0;
      const unsigned long index = std::stoul(text, &used, 0);
      unsigned long sub = 0;
      if (used < text.size()) {
        if (text[used] != ':') throw std::invalid_argument("separator");
        std::size_t used_sub = 0;
        sub = std::stoul(text.substr(used + 1), &used_sub, 0);
        if (used + 1 + used_sub != text.size()) throw std::invalid_argument("trailing");
      }
      if (index < 0x2000 || index > 0xFFFF || sub > 0xFF) throw std::out_of_range("range");
      t.index = static_cast<std::uint16_t>(index);
      t.sub = static_cast<std::uint8_t>(sub);
    } catch (const std::logic_error&) {
      bad(s + ".object", o, "INDEX[:SUB] like \"0x6130:1\" with 0x2000 <= INDEX <= 0xFFFF");
    }
  }
  if (const YAML::Node ty = n["type"]) {
    try {
      t.type = parse_process_value_type(ty.IsScalar() ? ty.Scalar() : "");
    } catch (const std::invalid_argument&) {
      bad(s + ".type", ty, "i16, i32 or f32");
    }
  }
  read_double(n, s, "scale", t.scale_nm_per_unit, 1e-12, 1e6);
  read_double(n, s, "noise_nm", t.noise_nm, 0, 1e4);
  read_double(n, s, "offset_nm", t.offset_nm, -1e6, 1e6);
  read_integer(n, s, "seed", t.seed, 0, std::numeric_limits<long long>::max());
}

}  // namespace

DataType parse_process_value_type(const std::string& text) {
  if (text == "i16" || text == "int16") return DataType::kInteger16;
  if (text == "i32" || text == "int32") return DataType::kInteger32;
  if (text == "f32" || text == "real32") return DataType::kReal32;
  throw std::invalid_argument("process value type '" + text + "' (expected i16, i32 or f32)");
}

SimulatedBenchConfig parse_simulated_bench_config(const std::string& yaml_text,
                                                  SimulatedBenchConfig base) {
  return parse_simulated_bench_config(yaml_text, "simbench config", std::move(base));
}

SimulatedBenchConfig parse_simulated_bench_config(const std::string& yaml_text,
                                                  const std::string& source,
                                                  SimulatedBenchConfig base) {
  YAML::Node root;
  try {
    root = strict_yaml::parse_strict_yaml(yaml_text, source);
  } catch (const strict_yaml::RefusedConfig& e) {
    throw std::invalid_argument(e.what());
  }
  if (!root.IsMap()) bad("(document)", root, "a map with a simbench section");
  const YAML::Node sb = root["simbench"];
  if (!sb) return base;
  check_keys(sb, "simbench",
             {"clock", "sync_period_us", "brake_torque_nm", "drive", "encoder", "torque_sensor",
              "input_encoder"});
  if (const YAML::Node c = sb["clock"]) {
    const std::string v = c.IsScalar() ? c.Scalar() : "";
    if (v == "realtime") {
      base.clock = BenchClock::kRealTime;
    } else if (v == "sync") {
      base.clock = BenchClock::kSyncDriven;
    } else if (v == "manual") {
      base.clock = BenchClock::kManual;
    } else {
      bad("simbench.clock", c, "realtime, sync or manual");
    }
  }
  double sync_us = base.sync_period * 1e6;
  read_double(sb, "simbench", "sync_period_us", sync_us, 10, 1e6);
  base.sync_period = sync_us * 1e-6;
  read_double(sb, "simbench", "brake_torque_nm", base.brake_torque, 0, 1e6);
  if (const YAML::Node d = sb["drive"]) read_drive(d, base.drive);
  if (const YAML::Node e = sb["encoder"]) read_encoder(e, base.encoder);
  if (const YAML::Node t = sb["torque_sensor"]) read_torque_sensor(t, base.torque_sensor);
  if (const YAML::Node e = sb["input_encoder"]) {
    if (!base.input_encoder) {
      EncoderConfig input;
      input.node_id = 5;
      input.identity.device_name = "WB-SIM input encoder";
      input.identity.product_code = 0x00000A58;
      input.revolutions = 1;  // single-turn on the fast shaft: it wraps every input turn
      input.seed = 5;
      base.input_encoder = input;
    }
    read_encoder(e, *base.input_encoder, "simbench.input_encoder");
  }
  const std::uint8_t ids[] = {base.drive.node_id, base.encoder.node_id, base.torque_sensor.node_id};
  if (ids[0] == ids[1] || ids[0] == ids[2] || ids[1] == ids[2]) {
    bad("simbench.*.node_id",
        std::to_string(ids[0]) + ", " + std::to_string(ids[1]) + ", " + std::to_string(ids[2]),
        "three different node ids");
  }
  if (base.input_encoder &&
      (base.input_encoder->node_id == ids[0] || base.input_encoder->node_id == ids[1] ||
       base.input_encoder->node_id == ids[2])) {
    throw std::invalid_argument(
        "simbench.input_encoder.node_id: " + std::to_string(base.input_encoder->node_id) +
        " (expected a node id no other simulated device uses)");
  }
  return base;
}

SimulatedBenchConfig load_simulated_bench_config(const std::filesystem::path& path,
                                                 SimulatedBenchConfig base) {
  std::string text;
  try {
    text = strict_yaml::read_config_file(path);
  } catch (const strict_yaml::RefusedConfig& e) {
    throw std::invalid_argument(e.what());
  }
  return parse_simulated_bench_config(text, path.string(), std::move(base));
}

}  // namespace wavebench::simdevices
