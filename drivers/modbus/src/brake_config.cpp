#include "wavebench/modbus/brake_config.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "wavebench/strict_yaml/strict_yaml.hpp"

namespace wavebench::modbus {

namespace {

// The message format of every config loader (strict_yaml::RefusedConfig).
[[noreturn]] void fail(const std::string& key, const std::string& value,
                       const std::string& expected) {
  throw BrakeConfigError(strict_yaml::RefusedConfig(key, value, expected, "brake config").what());
}

std::string text_of(const YAML::Node& n) {
  if (n.IsScalar()) return n.Scalar();
  if (n.IsMap()) return "<map>";
  if (n.IsSequence()) return "<list>";
  return "<null>";
}

void check_keys(const YAML::Node& node, const std::string& path,
                const std::set<std::string>& allowed) {
  if (!node.IsMap()) fail(path, text_of(node), "a map");
  for (const auto& kv : node) {
    const std::string key = kv.first.as<std::string>();
    if (!allowed.contains(key)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(path + "." + key, text_of(kv.second), "no such key (known: " + list + ")");
    }
  }
}

double read_double(const YAML::Node& n, const std::string& key, double lo, double hi) {
  double v = 0.0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    fail(key, text_of(n), "a number");
  }
  if (!std::isfinite(v) || v < lo || v > hi) {
    fail(key, text_of(n), "a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return v;
}

int read_int(const YAML::Node& n, const std::string& key, int lo, int hi) {
  long long v = 0;
  try {
    v = n.as<long long>();
  } catch (const YAML::Exception&) {
    fail(key, text_of(n), "an integer");
  }
  if (v < lo || v > hi) {
    fail(key, text_of(n), "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return static_cast<int>(v);
}

std::chrono::milliseconds read_ms(const YAML::Node& n, const std::string& key, int lo, int hi) {
  return std::chrono::milliseconds(read_int(n, key, lo, hi));
}

std::string read_string(const YAML::Node& n, const std::string& key) {
  if (!n.IsScalar()) fail(key, text_of(n), "a string");
  return n.Scalar();
}

template <typename F>
void optional(const YAML::Node& parent, const char* name, F&& f) {
  if (const YAML::Node n = parent[name]; n) f(n);
}

RegisterSpec read_spec(const YAML::Node& n, const std::string& key, RegisterSpec spec) {
  check_keys(n, key, {"table", "address", "type", "scale", "offset"});
  optional(n, "table", [&](const YAML::Node& v) {
    const std::string t = read_string(v, key + ".table");
    if (t == "holding") {
      spec.table = RegisterTable::holding;
    } else if (t == "input") {
      spec.table = RegisterTable::input;
    } else {
      fail(key + ".table", t, "holding or input");
    }
  });
  optional(n, "address",
           [&](const YAML::Node& v) { spec.address = read_int(v, key + ".address", 0, 65535); });
  optional(n, "type", [&](const YAML::Node& v) {
    const std::string t = read_string(v, key + ".type");
    static const std::pair<const char*, DataType> types[] = {{"uint16", DataType::uint16},
                                                             {"int16", DataType::int16},
                                                             {"uint32", DataType::uint32},
                                                             {"int32", DataType::int32},
                                                             {"float32", DataType::float32}};
    bool found = false;
    for (const auto& [name, type] : types) {
      if (t == name) {
        spec.type = type;
        found = true;
      }
    }
    if (!found) fail(key + ".type", t, "one of uint16, int16, uint32, int32, float32");
  });
  optional(n, "scale", [&](const YAML::Node& v) {
    spec.scale = read_double(v, key + ".scale", -1e9, 1e9);
    if (spec.scale == 0.0) fail(key + ".scale", text_of(v), "a non-zero number");
  });
  optional(n, "offset",
           [&](const YAML::Node& v) { spec.offset = read_double(v, key + ".offset", -1e9, 1e9); });
  if (spec.address + register_count(spec.type) - 1 > 65535) {
    fail(key + ".address", std::to_string(spec.address), "room for the value below 65536");
  }
  return spec;
}

void read_map(const YAML::Node& n, BrakeRegisterMap& map) {
  const std::string p = "map";
  check_keys(n, p,
             {"word_order", "control", "watchdog_timeout", "heartbeat", "setpoint", "setpoint_ramp",
              "status", "coil_current", "torque", "temperature", "slip_power", "alarm_code",
              "control_bits", "status_bits", "alarm_texts"});
  optional(n, "word_order", [&](const YAML::Node& v) {
    const std::string t = read_string(v, p + ".word_order");
    if (t == "abcd" || t == "ABCD") {
      map.word_order = WordOrder::abcd;
    } else if (t == "cdab" || t == "CDAB") {
      map.word_order = WordOrder::cdab;
    } else if (t == "badc" || t == "BADC") {
      map.word_order = WordOrder::badc;
    } else if (t == "dcba" || t == "DCBA") {
      map.word_order = WordOrder::dcba;
    } else {
      fail(p + ".word_order", t, "one of abcd, cdab, badc, dcba");
    }
  });
  const std::pair<const char*, RegisterSpec*> specs[] = {
      {"control", &map.control},
      {"watchdog_timeout", &map.watchdog_timeout_ms},
      {"heartbeat", &map.heartbeat},
      {"setpoint", &map.setpoint},
      {"setpoint_ramp", &map.setpoint_ramp},
      {"status", &map.status},
      {"coil_current", &map.coil_current},
      {"torque", &map.torque},
      {"temperature", &map.temperature},
      {"slip_power", &map.slip_power},
      {"alarm_code", &map.alarm_code}};
  // Plain copies of the bindings: clang before 16 cannot capture structured bindings.
  for (const auto& entry : specs) {
    const char* name = entry.first;
    RegisterSpec* spec = entry.second;
    optional(n, name, [&](const YAML::Node& v) { *spec = read_spec(v, p + "." + name, *spec); });
  }
  for (const char* name :
       {"control", "watchdog_timeout", "heartbeat", "setpoint", "setpoint_ramp"}) {
    for (const auto& [sname, spec] : specs) {
      if (std::string(sname) == name && spec->table != RegisterTable::holding) {
        fail(p + "." + name + ".table", "input", "holding (the client writes this register)");
      }
    }
  }
  optional(n, "control_bits", [&](const YAML::Node& v) {
    const std::string k = p + ".control_bits";
    check_keys(v, k, {"enable", "reset_alarm", "torque_mode"});
    optional(v, "enable",
             [&](auto& b) { map.control_bits.enable = read_int(b, k + ".enable", 0, 15); });
    optional(v, "reset_alarm", [&](auto& b) {
      map.control_bits.reset_alarm = read_int(b, k + ".reset_alarm", 0, 15);
    });
    optional(v, "torque_mode", [&](auto& b) {
      map.control_bits.torque_mode = read_int(b, k + ".torque_mode", 0, 15);
    });
  });
  optional(n, "status_bits", [&](const YAML::Node& v) {
    const std::string k = p + ".status_bits";
    check_keys(
        v, k,
        {"output_on", "alarm", "over_temperature", "watchdog_tripped", "coil_open", "at_setpoint"});
    const std::pair<const char*, int*> bits[] = {
        {"output_on", &map.status_bits.output_on},
        {"alarm", &map.status_bits.alarm},
        {"over_temperature", &map.status_bits.over_temperature},
        {"watchdog_tripped", &map.status_bits.watchdog_tripped},
        {"coil_open", &map.status_bits.coil_open},
        {"at_setpoint", &map.status_bits.at_setpoint}};
    for (const auto& entry : bits) {
      const char* name = entry.first;
      int* bit = entry.second;
      optional(v, name, [&](auto& b) { *bit = read_int(b, k + "." + name, 0, 15); });
    }
  });
  optional(n, "alarm_texts", [&](const YAML::Node& v) {
    if (!v.IsMap()) fail(p + ".alarm_texts", text_of(v), "a map of alarm code to text");
    map.alarm_texts.clear();
    for (const auto& kv : v) {
      const std::string k = p + ".alarm_texts." + kv.first.as<std::string>();
      map.alarm_texts[read_int(kv.first, k, 0, 65535)] = read_string(kv.second, k);
    }
  });
}

}  // namespace

BrakeClientConfig load_brake_config(const YAML::Node& node) {
  BrakeClientConfig cfg;
  if (!node || node.IsNull()) return cfg;
  check_keys(node, "brake", {"link", "timeouts", "reconnect", "heartbeat", "limits", "map"});
  optional(node, "link", [&](const YAML::Node& n) {
    check_keys(n, "link",
               {"endpoint", "transport", "host", "port", "device", "baud", "parity", "data_bits",
                "stop_bits", "unit_id"});
    auto& ep = cfg.link.endpoint;
    optional(n, "endpoint", [&](const YAML::Node& v) {
      const std::string text = read_string(v, "link.endpoint");
      try {
        ep = parse_modbus_endpoint(text);
      } catch (const std::invalid_argument& e) {
        fail("link.endpoint", text,
             "tcp:HOST:PORT or rtu:DEVICE[:BAUD...] (" + std::string(e.what()) + ")");
      }
    });
    optional(n, "transport", [&](const YAML::Node& v) {
      const std::string t = read_string(v, "link.transport");
      if (t == "tcp") {
        ep.transport = Transport::tcp;
      } else if (t == "rtu") {
        ep.transport = Transport::rtu;
      } else {
        fail("link.transport", t, "tcp or rtu");
      }
    });
    optional(n, "host", [&](const YAML::Node& v) { ep.host = read_string(v, "link.host"); });
    optional(n, "port", [&](const YAML::Node& v) { ep.port = read_int(v, "link.port", 0, 65535); });
    optional(n, "device", [&](const YAML::Node& v) { ep.device = read_string(v, "link.device"); });
    optional(n, "baud",
             [&](const YAML::Node& v) { ep.baud = read_int(v, "link.baud", 1, 4000000); });
    optional(n, "parity", [&](const YAML::Node& v) {
      const std::string t = read_string(v, "link.parity");
      if (t != "N" && t != "E" && t != "O") fail("link.parity", t, "N, E or O");
      ep.parity = t[0];
    });
    optional(n, "data_bits",
             [&](const YAML::Node& v) { ep.data_bits = read_int(v, "link.data_bits", 5, 8); });
    optional(n, "stop_bits",
             [&](const YAML::Node& v) { ep.stop_bits = read_int(v, "link.stop_bits", 1, 2); });
    optional(n, "unit_id",
             [&](const YAML::Node& v) { cfg.link.unit_id = read_int(v, "link.unit_id", 0, 255); });
    if (ep.transport == Transport::rtu && ep.device.empty()) {
      fail("link.device", "", "a serial device path for the rtu transport");
    }
  });
  optional(node, "timeouts", [&](const YAML::Node& n) {
    check_keys(n, "timeouts", {"response_ms", "byte_ms", "link_loss_ms"});
    optional(n, "response_ms", [&](const YAML::Node& v) {
      cfg.link.response_timeout = read_ms(v, "timeouts.response_ms", 1, 60000);
    });
    optional(n, "byte_ms", [&](const YAML::Node& v) {
      cfg.link.byte_timeout = read_ms(v, "timeouts.byte_ms", 1, 60000);
    });
    optional(n, "link_loss_ms", [&](const YAML::Node& v) {
      cfg.link.link_loss_timeout = read_ms(v, "timeouts.link_loss_ms", 1, 600000);
    });
  });
  optional(node, "reconnect", [&](const YAML::Node& n) {
    check_keys(n, "reconnect", {"initial_backoff_ms", "max_backoff_ms"});
    optional(n, "initial_backoff_ms", [&](const YAML::Node& v) {
      cfg.link.reconnect_initial_backoff = read_ms(v, "reconnect.initial_backoff_ms", 1, 600000);
    });
    optional(n, "max_backoff_ms", [&](const YAML::Node& v) {
      cfg.link.reconnect_max_backoff = read_ms(v, "reconnect.max_backoff_ms", 1, 600000);
    });
    if (cfg.link.reconnect_max_backoff < cfg.link.reconnect_initial_backoff) {
      fail("reconnect.max_backoff_ms", std::to_string(cfg.link.reconnect_max_backoff.count()),
           "at least reconnect.initial_backoff_ms (" +
               std::to_string(cfg.link.reconnect_initial_backoff.count()) + ")");
    }
  });
  optional(node, "heartbeat", [&](const YAML::Node& n) {
    check_keys(n, "heartbeat", {"period_ms", "watchdog_ms"});
    optional(n, "period_ms", [&](const YAML::Node& v) {
      cfg.heartbeat.period = read_ms(v, "heartbeat.period_ms", 1, 60000);
    });
    optional(n, "watchdog_ms", [&](const YAML::Node& v) {
      cfg.heartbeat.watchdog_timeout = read_ms(v, "heartbeat.watchdog_ms", 0, 65535);
    });
    if (cfg.heartbeat.watchdog_timeout.count() != 0 &&
        cfg.heartbeat.watchdog_timeout <= cfg.heartbeat.period) {
      fail("heartbeat.watchdog_ms", std::to_string(cfg.heartbeat.watchdog_timeout.count()),
           "0 (off) or longer than heartbeat.period_ms (" +
               std::to_string(cfg.heartbeat.period.count()) + ")");
    }
  });
  optional(node, "limits", [&](const YAML::Node& n) {
    check_keys(n, "limits", {"max_current_a", "max_torque_nm", "max_ramp_per_s"});
    optional(n, "max_current_a", [&](const YAML::Node& v) {
      cfg.limits.max_current_a = read_double(v, "limits.max_current_a", 0.0, 1000.0);
    });
    optional(n, "max_torque_nm", [&](const YAML::Node& v) {
      cfg.limits.max_torque_nm = read_double(v, "limits.max_torque_nm", 0.0, 1e6);
    });
    optional(n, "max_ramp_per_s", [&](const YAML::Node& v) {
      cfg.limits.max_ramp_per_s = read_double(v, "limits.max_ramp_per_s", 0.0, 1e9);
    });
  });
  optional(node, "map", [&](const YAML::Node& n) { read_map(n, cfg.map); });
  return cfg;
}

BrakeClientConfig load_brake_config_file(const std::filesystem::path& path) {
  YAML::Node root;
  try {
    root = strict_yaml::parse_strict_yaml(strict_yaml::read_config_file(path), path.string());
  } catch (const strict_yaml::RefusedConfig& e) {
    throw BrakeConfigError(e.what());
  }
  if (root.IsMap() && root["brake"]) {
    if (root["brake"].IsNull()) fail("brake", "", "a section of brake settings (it is empty)");
    return load_brake_config(root["brake"]);
  }
  return load_brake_config(root);
}

}  // namespace wavebench::modbus
