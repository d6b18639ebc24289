#include "wavebench/bench/bench_config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <set>
#include <sstream>

#include "wavebench/config/config_error.hpp"
#include "wavebench/config/config_text.hpp"
#include "wavebench/config/twin_case.hpp"
#include "wavebench/config/units.hpp"
#include "wavebench/simdevices/simulated_bench_config.hpp"
#include "wavebench/storage/sync_sample.hpp"

#ifndef WAVEBENCH_CONFIG_DIR
#define WAVEBENCH_CONFIG_DIR "configs"
#endif

namespace wavebench::bench {
namespace {

using config::ConfigError;
using config::Dimension;

std::string scalar_text(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  std::ostringstream out;
  out << node;
  return out.str();
}

void check_keys(const YAML::Node& node, const std::string& section,
                const std::set<std::string>& allowed) {
  if (!node.IsMap()) throw ConfigError(section, scalar_text(node), "a mapping");
  for (const auto& item : node) {
    const auto key = item.first.as<std::string>();
    if (!allowed.contains(key)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw ConfigError(section.empty() ? key : section + "." + key, scalar_text(item.second),
                        "one of the known keys: " + list);
    }
  }
}

double quantity(const YAML::Node& node, Dimension dim, const std::string& key) {
  if (!node.IsScalar()) throw ConfigError(key, scalar_text(node), config::describe(dim));
  return config::parse_quantity(node.Scalar(), dim, key);
}

double number(const YAML::Node& node, const std::string& key, double lo, double hi) {
  double v = 0;
  try {
    v = node.as<double>();
  } catch (const YAML::Exception&) {
    throw ConfigError(key, scalar_text(node), "a number");
  }
  if (!std::isfinite(v) || v < lo || v > hi) {
    std::ostringstream expected;
    expected << "a number in [" << lo << ", " << hi << "]";
    throw ConfigError(key, scalar_text(node), expected.str());
  }
  return v;
}

long integer(const YAML::Node& node, const std::string& key, long lo, long hi) {
  long v = 0;
  try {
    v = node.as<long>();
  } catch (const YAML::Exception&) {
    throw ConfigError(key, scalar_text(node), "an integer");
  }
  if (v < lo || v > hi) {
    throw ConfigError(key, scalar_text(node),
                      "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return v;
}

std::string text(const YAML::Node& node, const std::string& key) {
  if (!node.IsScalar()) throw ConfigError(key, scalar_text(node), "a string");
  return node.Scalar();
}

// Names and serials go into run folders, the runs index and report titles: one short line.
std::string label(const YAML::Node& node, const std::string& key) {
  std::string v = text(node, key);
  constexpr std::size_t kMaxLabel = 128;
  if (v.empty() || v.size() > kMaxLabel) {
    throw ConfigError(key, v, "a text of 1 to " + std::to_string(kMaxLabel) + " characters");
  }
  return v;
}

// A quantity in [lo, hi] (SI), for values whose extremes would stall or flood the bench.
double bounded_quantity(const YAML::Node& node, Dimension dim, const std::string& key, double lo,
                        double hi, const std::string& range) {
  const double v = quantity(node, dim, key);
  if (v < lo || v > hi) throw ConfigError(key, scalar_text(node), range);
  return v;
}

void optional(const YAML::Node& section, const char* key,
              const std::function<void(const YAML::Node&)>& read) {
  if (const auto n = section[key]; n) read(n);
}

std::filesystem::path resolve(const std::filesystem::path& base, const std::string& p) {
  std::filesystem::path path(p);
  return path.is_absolute() ? path : (base / path).lexically_normal();
}

// "0x6130:1" -> index, sub.
void parse_object(const std::string& value, const std::string& key, std::uint16_t& index,
                  std::uint8_t& sub) {
  const auto colon = value.find(':');
  try {
    std::size_t used = 0;
    const unsigned long i = std::stoul(value.substr(0, colon), &used, 0);
    if (used != (colon == std::string::npos ? value.size() : colon) || i > 0xFFFF)
      throw std::invalid_argument(value);
    unsigned long s = 0;
    if (colon != std::string::npos) {
      s = std::stoul(value.substr(colon + 1), &used, 0);
      if (used != value.size() - colon - 1 || s > 0xFF) throw std::invalid_argument(value);
    }
    index = static_cast<std::uint16_t>(i);
    sub = static_cast<std::uint8_t>(s);
  } catch (const std::exception&) {
    throw ConfigError(key, value, "an object as INDEX:SUB, e.g. \"0x6130:1\"");
  }
}

void read_top(const YAML::Node& root, BenchConfig& c, const std::filesystem::path& base) {
  auto& d = c.description;
  optional(root, "name", [&](const YAML::Node& n) { d.name = label(n, "name"); });
  optional(root, "unit_serial",
           [&](const YAML::Node& n) { d.unit_serial = label(n, "unit_serial"); });
  optional(root, "rated_torque", [&](const YAML::Node& n) {
    d.rated_torque_nm = quantity(n, Dimension::kTorque, "rated_torque");
    if (d.rated_torque_nm <= 0) throw ConfigError("rated_torque", scalar_text(n), "a torque > 0");
  });
  optional(root, "gear", [&](const YAML::Node& n) {
    check_keys(n, "gear", {"ratio", "direction_sign"});
    optional(n, "ratio",
             [&](const YAML::Node& v) { d.sense.ratio = number(v, "gear.ratio", 1e-3, 1e6); });
    optional(n, "direction_sign", [&](const YAML::Node& v) {
      const long s = integer(v, "gear.direction_sign", -1, 1);
      if (s == 0) throw ConfigError("gear.direction_sign", "0", "+1 or -1");
      d.sense.direction_sign = static_cast<int>(s);
    });
  });
  optional(root, "sync_period", [&](const YAML::Node& n) {
    d.sync_period_s = quantity(n, Dimension::kTime, "sync_period");
    if (d.sync_period_s < 1e-4 || d.sync_period_s > 1.0)
      throw ConfigError("sync_period", scalar_text(n), "a period between 100 us and 1 s");
    if (std::abs(std::round(d.sync_period_s * 1e6) - d.sync_period_s * 1e6) > 1e-6)
      throw ConfigError("sync_period", scalar_text(n), "a whole number of microseconds");
  });
  optional(root, "clock", [&](const YAML::Node& n) {
    const auto v = text(n, "clock");
    if (v == "real") {
      c.clock = BenchClockKind::kReal;
    } else if (v == "simulated") {
      c.clock = BenchClockKind::kSimulated;
    } else {
      throw ConfigError("clock", v, "real or simulated");
    }
  });
  optional(root, "twin_case", [&](const YAML::Node& n) {
    d.twin_case_path = resolve(base, text(n, "twin_case")).string();
  });
}

void read_can(const YAML::Node& n, CanSettings& can) {
  check_keys(n, "can",
             {"interface", "bitrate", "sdo_timeout", "heartbeat_producer", "nodes",
              "bus_load_warning", "cycle_timeout", "quick_stop_timeout"});
  optional(n, "interface", [&](const YAML::Node& v) {
    can.interface = text(v, "can.interface");
    if (can.interface.empty())
      throw ConfigError("can.interface", "", "inproc or an interface name");
  });
  optional(n, "bitrate",
           [&](const YAML::Node& v) { can.bitrate = number(v, "can.bitrate", 1e4, 1e7); });
  optional(n, "sdo_timeout", [&](const YAML::Node& v) {
    can.sdo_timeout_s = quantity(v, Dimension::kTime, "can.sdo_timeout");
    if (can.sdo_timeout_s <= 0) throw ConfigError("can.sdo_timeout", scalar_text(v), "a time > 0");
  });
  optional(n, "heartbeat_producer", [&](const YAML::Node& v) {
    can.heartbeat_producer_s = quantity(v, Dimension::kTime, "can.heartbeat_producer");
    if (can.heartbeat_producer_s < 1e-3 || can.heartbeat_producer_s > 65.535)
      throw ConfigError("can.heartbeat_producer", scalar_text(v), "a time in [1 ms, 65.535 s]");
  });
  optional(n, "bus_load_warning", [&](const YAML::Node& v) {
    can.bus_load_warning = number(v, "can.bus_load_warning", 0, 10);
  });
  optional(n, "cycle_timeout", [&](const YAML::Node& v) {
    can.cycle_timeout_s = quantity(v, Dimension::kTime, "can.cycle_timeout");
    if (can.cycle_timeout_s <= 0)
      throw ConfigError("can.cycle_timeout", scalar_text(v), "a time > 0");
  });
  optional(n, "quick_stop_timeout", [&](const YAML::Node& v) {
    can.quick_stop_timeout_s = quantity(v, Dimension::kTime, "can.quick_stop_timeout");
    if (!(can.quick_stop_timeout_s > 0) || can.quick_stop_timeout_s > 10)
      throw ConfigError("can.quick_stop_timeout", scalar_text(v), "a time in (0, 10 s]");
  });
  optional(n, "nodes", [&](const YAML::Node& v) {
    check_keys(v, "can.nodes", {"drive", "encoder", "torque_sensor"});
    auto node = [&](const char* key, std::uint8_t& out) {
      optional(v, key, [&](const YAML::Node& x) {
        out = static_cast<std::uint8_t>(integer(x, std::string("can.nodes.") + key, 1, 127));
      });
    };
    node("drive", can.drive_node);
    node("encoder", can.encoder_node);
    node("torque_sensor", can.torque_node);
  });
  if (can.drive_node == can.encoder_node || can.drive_node == can.torque_node ||
      can.encoder_node == can.torque_node) {
    throw ConfigError("can.nodes",
                      std::to_string(can.drive_node) + ", " + std::to_string(can.encoder_node) +
                          ", " + std::to_string(can.torque_node),
                      "three different node ids");
  }
}

// `eds:` and `identity:` of a CANopen device section.
void read_expectations(const YAML::Node& n, const std::string& section,
                       const std::filesystem::path& base, NodeExpectations& e) {
  optional(n, "eds", [&](const YAML::Node& v) {
    const auto path = resolve(base, text(v, section + ".eds"));
    try {
      e.eds = std::make_shared<const canopen::Eds>(canopen::Eds::load(path));
    } catch (const canopen::EdsError& error) {
      throw ConfigError(section + ".eds", path.string(),
                        std::string("a CiA 306 EDS: ") + error.what());
    }
    e.eds_path = path;
  });
  optional(n, "identity", [&](const YAML::Node& id) {
    check_keys(id, section + ".identity",
               {"vendor_id", "product_code", "revision", "serial_number"});
    auto read = [&](const char* key, std::optional<std::uint32_t>& out) {
      optional(id, key, [&](const YAML::Node& v) {
        out = static_cast<std::uint32_t>(integer(v, section + ".identity." + key, 0, 0xFFFFFFFFL));
      });
    };
    read("vendor_id", e.identity.vendor_id);
    read("product_code", e.identity.product_code);
    read("revision", e.identity.revision);
    read("serial_number", e.identity.serial_number);
  });
}

// Where the config is silent, values from the devices' EDS files: the torque sensor's data type
// (the DataType of its object). The encoder's resolution and turns stay read from the device
// (0x6501/0x6502), which knows its own configuration better than a data sheet's defaults.
void apply_eds_defaults(const YAML::Node& root, BenchConfig& c) {
  const auto given = [&](const char* section, const char* key) {
    return root[section] && root[section][key];
  };
  auto& sensor = c.torque_sensor.sensor;
  if (!given("torque_sensor", "type") && c.torque_sensor.expect.eds) {
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

void read_drive_units(const YAML::Node& n, DriveSettings& d) {
  const auto unit = [&](const char* key, DriveQuantity q, DriveUnitChoice& out) {
    optional(n, key, [&](const YAML::Node& v) {
      const std::string name = std::string("drive.") + key;
      const auto t = text(v, name);
      try {
        out = parse_drive_unit(t, q);
      } catch (const std::invalid_argument& e) {
        throw ConfigError(name, t, e.what());
      }
    });
  };
  unit("position_unit", DriveQuantity::kPosition, d.position_unit);
  unit("velocity_unit", DriveQuantity::kVelocity, d.velocity_unit);
  unit("acceleration_unit", DriveQuantity::kAcceleration, d.acceleration_unit);
  optional(n, "torque_actual_scale", [&](const YAML::Node& v) {
    const auto t = text(v, "drive.torque_actual_scale");
    if (t == "rated") {
      d.torque_actual_nm_per_unit.reset();
      return;
    }
    const std::string expected =
        "rated (per mille of the drive's rated torque 0x6076) or a torque > 0 per unit of 0x6077 "
        "(\"0.001 N*m\")";
    double scale = 0;
    try {
      scale = config::parse_quantity(t, Dimension::kTorque, "drive.torque_actual_scale");
    } catch (const ConfigError&) {
      throw ConfigError("drive.torque_actual_scale", t, expected);
    }
    if (!(scale > 0)) throw ConfigError("drive.torque_actual_scale", t, expected);
    d.torque_actual_nm_per_unit = scale;
  });
}

void read_devices(const YAML::Node& root, BenchConfig& c, const std::filesystem::path& base) {
  optional(root, "drive", [&](const YAML::Node& n) {
    check_keys(n, "drive",
               {"counts_per_revolution", "profile_acceleration", "target_settle", "position_unit",
                "velocity_unit", "acceleration_unit", "torque_actual_scale", "eds", "identity"});
    read_expectations(n, "drive", base, c.drive.expect);
    optional(n, "counts_per_revolution", [&](const YAML::Node& v) {
      c.drive.counts_per_revolution =
          static_cast<std::uint32_t>(integer(v, "drive.counts_per_revolution", 1, 1L << 31));
    });
    optional(n, "profile_acceleration", [&](const YAML::Node& v) {
      c.drive.profile_acceleration_rad_s2 = number(v, "drive.profile_acceleration", 0, 1e9);
    });
    optional(n, "target_settle", [&](const YAML::Node& v) {
      c.drive.target_settle_s = bounded_quantity(v, Dimension::kTime, "drive.target_settle", 0, 60,
                                                 "a time in [0, 60 s]");
    });
    read_drive_units(n, c.drive);
  });
  optional(root, "encoder", [&](const YAML::Node& n) {
    check_keys(n, "encoder", {"counts_per_turn", "turns", "noise", "eds", "identity"});
    read_expectations(n, "encoder", base, c.encoder.expect);
    optional(n, "counts_per_turn", [&](const YAML::Node& v) {
      c.encoder.counts_per_turn =
          static_cast<std::uint32_t>(integer(v, "encoder.counts_per_turn", 2, 1L << 31));
    });
    optional(n, "turns", [&](const YAML::Node& v) {
      c.encoder.turns = static_cast<std::uint32_t>(integer(v, "encoder.turns", 1, 1L << 20));
    });
    optional(n, "noise", [&](const YAML::Node& v) {
      c.encoder.noise_rad = bounded_quantity(v, Dimension::kAngle, "encoder.noise", 0, M_PI / 180,
                                             "an angle in [0, 1 deg]");
    });
  });
  optional(root, "torque_sensor", [&](const YAML::Node& n) {
    check_keys(n, "torque_sensor",
               {"object", "type", "scale", "offset", "noise", "eds", "identity"});
    read_expectations(n, "torque_sensor", base, c.torque_sensor.expect);
    auto& s = c.torque_sensor.sensor;
    optional(n, "object", [&](const YAML::Node& v) {
      parse_object(text(v, "torque_sensor.object"), "torque_sensor.object", s.index, s.sub);
    });
    optional(n, "type", [&](const YAML::Node& v) {
      const auto t = text(v, "torque_sensor.type");
      const auto type = canopen::parse_value_type(t);
      if (!type)
        throw ConfigError("torque_sensor.type", t, "u8, u16, u32, i8, i16, i32, f32 or f64");
      s.type = *type;
    });
    optional(n, "scale", [&](const YAML::Node& v) {
      s.scale = number(v, "torque_sensor.scale", -1e9, 1e9);
      if (s.scale == 0)
        throw ConfigError("torque_sensor.scale", "0", "a non-zero N*m per raw unit");
    });
    optional(n, "offset", [&](const YAML::Node& v) {
      s.offset = bounded_quantity(v, Dimension::kTorque, "torque_sensor.offset", -1e6, 1e6,
                                  "a torque in [-1e6, 1e6] N*m");
    });
    optional(n, "noise", [&](const YAML::Node& v) {
      c.torque_sensor.noise_nm = bounded_quantity(v, Dimension::kTorque, "torque_sensor.noise", 0,
                                                  1e4, "a torque in [0, 1e4] N*m");
    });
  });
}

// `devices:`: channel name -> {kind, node, sign, the kind's keys}. Kinds come from the
// registry (device_kind_registry.cpp), so a new kind needs no change here beyond its keys.
void read_channel_devices(const YAML::Node& root, BenchConfig& c) {
  optional(root, "devices", [&](const YAML::Node& n) {
    if (!n.IsMap()) throw ConfigError("devices", scalar_text(n), "a mapping of channel names");
    std::set<int> nodes{c.can.drive_node, c.can.encoder_node, c.can.torque_node};
    for (const auto& item : n) {
      ChannelDeviceSettings d;
      d.channel = item.first.as<std::string>();
      const std::string where = "devices." + d.channel;
      try {
        storage::check_extra_channels(std::vector<storage::ChannelInfo>{{d.channel, "rad"}});
      } catch (const std::invalid_argument& e) {
        throw ConfigError("devices", d.channel,
                          "a channel name of [a-z0-9_], 1..31 bytes, "
                          "not a core channel's (" +
                              std::string(e.what()) + ")");
      }
      const YAML::Node& v = item.second;
      if (!v.IsMap()) throw ConfigError(where, scalar_text(v), "a mapping with kind and node");
      if (!v["kind"]) throw ConfigError(where + ".kind", "(missing)", "a device kind");
      d.kind = text(v["kind"], where + ".kind");
      const auto* kind = find_channel_device_kind(d.kind);
      if (!kind) {
        std::string list;
        for (const auto& k : channel_device_kinds()) list += (list.empty() ? "" : ", ") + k.kind;
        throw ConfigError(where + ".kind", d.kind, "one of " + list);
      }
      std::set<std::string> allowed{"kind", "node", "sign"};
      allowed.insert(kind->keys.begin(), kind->keys.end());
      check_keys(v, where, allowed);
      if (!v["node"]) throw ConfigError(where + ".node", "(missing)", "a node id in [1, 127]");
      d.node = static_cast<std::uint8_t>(integer(v["node"], where + ".node", 1, 127));
      if (!nodes.insert(d.node).second)
        throw ConfigError(where + ".node", std::to_string(d.node),
                          "a node id no other device of the bench uses");
      optional(v, "sign", [&](const YAML::Node& x) {
        const long sign = integer(x, where + ".sign", -1, 1);
        if (sign == 0) throw ConfigError(where + ".sign", "0", "1 or -1");
        d.sign = static_cast<int>(sign);
      });
      optional(v, "counts_per_turn", [&](const YAML::Node& x) {
        d.counts_per_turn =
            static_cast<std::uint32_t>(integer(x, where + ".counts_per_turn", 2, 1L << 31));
      });
      optional(v, "turns", [&](const YAML::Node& x) {
        d.turns = static_cast<std::uint32_t>(integer(x, where + ".turns", 1, 1L << 20));
      });
      optional(v, "object", [&](const YAML::Node& x) {
        parse_object(text(x, where + ".object"), where + ".object", d.torque.index, d.torque.sub);
      });
      optional(v, "type", [&](const YAML::Node& x) {
        const auto t = text(x, where + ".type");
        const auto type = canopen::parse_value_type(t);
        if (!type) throw ConfigError(where + ".type", t, "u8, u16, u32, i8, i16, i32, f32 or f64");
        d.torque.type = *type;
      });
      optional(v, "scale", [&](const YAML::Node& x) {
        d.torque.scale = number(x, where + ".scale", -1e9, 1e9);
        if (d.torque.scale == 0) throw ConfigError(where + ".scale", "0", "a non-zero scale");
      });
      optional(v, "offset", [&](const YAML::Node& x) {
        d.torque.offset = bounded_quantity(x, Dimension::kTorque, where + ".offset", -1e6, 1e6,
                                           "a torque in [-1e6, 1e6] N*m");
      });
      if (c.devices.size() == storage::kMaxExtraChannels)
        throw ConfigError("devices", std::to_string(n.size()) + " devices",
                          "at most " + std::to_string(storage::kMaxExtraChannels));
      c.devices.push_back(std::move(d));
    }
  });
}

void read_safety(const YAML::Node& n, SafetyLimits& l) {
  check_keys(n, "safety",
             {"max_input_speed", "max_brake_current", "max_brake_torque", "max_measured_torque",
              "max_following_error", "max_coil_temperature", "max_te_excursion",
              "heartbeat_timeout", "modbus_link_timeout"});
  // An absent key switches its limit off; a written one must be a limit. A negative or zero
  // value used to mean "off" too, so a sign typo silently disarmed the bench.
  auto read = [&](const char* key, Dimension dim, double& out) {
    optional(n, key, [&](const YAML::Node& v) {
      const std::string name = std::string("safety.") + key;
      out = quantity(v, dim, name);
      if (!(out > 0)) {
        throw ConfigError(name, scalar_text(v),
                          "a limit > 0 (leave the key out to switch this limit off)");
      }
    });
  };
  read("max_input_speed", Dimension::kAngularSpeed, l.max_input_speed_rad_s);
  read("max_brake_current", Dimension::kCurrent, l.max_brake_current_a);
  read("max_brake_torque", Dimension::kTorque, l.max_brake_torque_nm);
  read("max_measured_torque", Dimension::kTorque, l.max_measured_torque_nm);
  read("max_following_error", Dimension::kAngle, l.max_following_error_rad);
  read("max_coil_temperature", Dimension::kTemperature, l.max_coil_temperature_c);
  read("max_te_excursion", Dimension::kAngle, l.max_te_excursion_rad);
  read("heartbeat_timeout", Dimension::kTime, l.heartbeat_timeout_s);
  read("modbus_link_timeout", Dimension::kTime, l.modbus_link_timeout_s);
}

void read_simulated(const YAML::Node& n, BenchConfig& c, const std::filesystem::path& base) {
  check_keys(n, "simulated", {"true_gear", "simbench", "brake_server"});
  SimulatedSettings s;
  s.true_gear_case =
      std::filesystem::path(WAVEBENCH_CONFIG_DIR) / "twin" / "bench-unit-seed004.yaml";
  optional(n, "true_gear", [&](const YAML::Node& g) {
    check_keys(g, "simulated.true_gear",
               {"case", "te_amplitude_scale", "te_phase_shift", "stiffness_scale", "backlash"});
    optional(g, "case", [&](const YAML::Node& v) {
      s.true_gear_case = resolve(base, text(v, "simulated.true_gear.case"));
    });
    optional(g, "te_amplitude_scale", [&](const YAML::Node& v) {
      s.variation.te_amplitude_scale = number(v, "simulated.true_gear.te_amplitude_scale", 0, 100);
    });
    optional(g, "te_phase_shift", [&](const YAML::Node& v) {
      s.variation.te_phase_shift_rad =
          bounded_quantity(v, Dimension::kAngle, "simulated.true_gear.te_phase_shift", -2 * M_PI,
                           2 * M_PI, "an angle in [-1 rev, 1 rev]");
    });
    optional(g, "stiffness_scale", [&](const YAML::Node& v) {
      s.variation.stiffness_scale = number(v, "simulated.true_gear.stiffness_scale", 1e-3, 1e3);
    });
    optional(g, "backlash", [&](const YAML::Node& v) {
      s.variation.backlash_rad =
          bounded_quantity(v, Dimension::kAngle, "simulated.true_gear.backlash", 0, M_PI / 180,
                           "an angle in [0, 1 deg]");
    });
  });
  optional(n, "brake_server", [&](const YAML::Node& v) {
    const auto t = text(v, "simulated.brake_server");
    if (t != "true" && t != "false")
      throw ConfigError("simulated.brake_server", t, "true or false");
    s.brake_server = t == "true";
  });
  optional(n, "simbench", [&](const YAML::Node& v) {
    YAML::Node wrapper;
    wrapper["simbench"] = v;
    std::ostringstream out;
    out << wrapper;
    try {
      s.devices = std::make_shared<const simdevices::SimulatedBenchConfig>(
          simdevices::parse_simulated_bench_config(out.str()));
      if (v.IsMap()) {
        if (v["drive"] && v["drive"]["node_id"]) s.drive_node = s.devices->drive.node_id;
        if (v["encoder"] && v["encoder"]["node_id"]) s.encoder_node = s.devices->encoder.node_id;
        if (v["torque_sensor"] && v["torque_sensor"]["node_id"])
          s.torque_node = s.devices->torque_sensor.node_id;
      }
    } catch (const std::invalid_argument& e) {
      throw ConfigError("simulated.simbench", scalar_text(v), e.what());
    }
  });
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
      (std::filesystem::path(WAVEBENCH_CONFIG_DIR) / "twin" / "bench-unit-seed004.yaml").string();
  c.brake.link.endpoint.port = 1502;
  try {
    const YAML::Node root = config::parse_config_yaml(yaml_text, source);
    check_keys(
        root, "",
        {"name", "unit_serial", "rated_torque", "gear", "sync_period", "clock", "twin_case", "can",
         "drive", "encoder", "torque_sensor", "devices", "brake", "safety", "simulated"});
    read_top(root, c, base_dir);
    optional(root, "can", [&](const YAML::Node& n) { read_can(n, c.can); });
    read_devices(root, c, base_dir);
    apply_eds_defaults(root, c);
    read_channel_devices(root, c);
    optional(root, "brake", [&](const YAML::Node& n) {
      try {
        c.brake = modbus::load_brake_config(n);
      } catch (const modbus::BrakeConfigError& e) {
        throw ConfigError("brake", scalar_text(n), e.what());
      }
    });
    optional(root, "safety", [&](const YAML::Node& n) { read_safety(n, c.description.limits); });
    if (c.description.limits.modbus_link_timeout_s > 0) {
      c.brake.link.link_loss_timeout =
          std::chrono::milliseconds(std::lround(c.description.limits.modbus_link_timeout_s * 1e3));
    }
    optional(root, "simulated", [&](const YAML::Node& n) { read_simulated(n, c, base_dir); });
    if (c.in_process() && !c.simulated)
      read_simulated(YAML::Node(YAML::NodeType::Map), c, base_dir);

    auto& d = c.description;
    d.simulated_clock = c.clock == BenchClockKind::kSimulated;
    d.max_brake_torque_nm = c.brake.limits.max_torque_nm;
    if (d.limits.max_brake_torque_nm > 0)
      d.max_brake_torque_nm = std::min(d.max_brake_torque_nm, d.limits.max_brake_torque_nm);
    d.input_encoder_resolution_rad = 2 * M_PI / c.drive.counts_per_revolution;
    d.output_encoder_noise_rad = c.encoder.noise_rad;
    d.torque_noise_nm = c.torque_sensor.noise_nm;
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
  // An installed wavebench names its configs folder in the environment; a build tree knows it.
  const char* dir = std::getenv("WAVEBENCH_CONFIG_DIR");
  const std::filesystem::path configs = dir != nullptr && *dir != 0 ? dir : WAVEBENCH_CONFIG_DIR;
  return load_bench_config(configs / "benches" / "sim.yaml");
}

BenchConfig bench_config_from_argument(const std::string& sim_or_path) {
  if (sim_or_path.empty() || sim_or_path == "sim") return default_simulated_bench_config();
  return load_bench_config(sim_or_path);
}

}  // namespace wavebench::bench
