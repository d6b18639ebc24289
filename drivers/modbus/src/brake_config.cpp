#include "wavebench/modbus/brake_config.hpp"

#include <yaml-cpp/yaml.h>

#include <utility>

namespace wavebench::modbus {

namespace {

using strict_yaml::set_if;
using strict_yaml::YamlSection;

void set_ms_if(std::optional<long long> v, std::chrono::milliseconds& out) {
  if (v) out = std::chrono::milliseconds(*v);
}

RegisterSpec read_spec(YamlSection& s, RegisterSpec spec) {
  if (const auto t = s.optional_choice("table", {"holding", "input"})) {
    spec.table = *t == "holding" ? RegisterTable::holding : RegisterTable::input;
  }
  set_if(s.optional_integer("address", 0, 65535), spec.address);
  static const std::pair<const char*, DataType> types[] = {{"uint16", DataType::uint16},
                                                           {"int16", DataType::int16},
                                                           {"uint32", DataType::uint32},
                                                           {"int32", DataType::int32},
                                                           {"float32", DataType::float32}};
  if (const auto t = s.optional_choice("type", {"uint16", "int16", "uint32", "int32", "float32"})) {
    for (const auto& [name, type] : types) {
      if (*t == name) spec.type = type;
    }
  }
  if (const auto v = s.optional_number("scale", -1e9, 1e9)) {
    if (*v == 0.0) s.fail("scale", s.value_text("scale"), "a non-zero number");
    spec.scale = *v;
  }
  if (const auto v = s.optional_number("offset", -1e9, 1e9)) spec.offset = *v;
  if (spec.address + register_count(spec.type) - 1 > 65535) {
    s.fail("address", std::to_string(spec.address), "room for the value below 65536");
  }
  s.finish();
  return spec;
}

void read_map(YamlSection& s, BrakeRegisterMap& map) {
  if (const auto t = s.optional_choice(
          "word_order", {"abcd", "cdab", "badc", "dcba", "ABCD", "CDAB", "BADC", "DCBA"})) {
    const char c = static_cast<char>(std::tolower(static_cast<unsigned char>((*t)[0])));
    map.word_order = c == 'a'   ? WordOrder::abcd
                     : c == 'c' ? WordOrder::cdab
                     : c == 'b' ? WordOrder::badc
                                : WordOrder::dcba;
  }
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
  for (const auto& [name, spec] : specs) {
    if (auto sub = s.optional_section(name)) *spec = read_spec(*sub, *spec);
  }
  for (const char* name :
       {"control", "watchdog_timeout", "heartbeat", "setpoint", "setpoint_ramp"}) {
    for (const auto& [sname, spec] : specs) {
      if (std::string(sname) == name && spec->table != RegisterTable::holding) {
        s.fail(std::string(name) + ".table", "input", "holding (the client writes this register)");
      }
    }
  }
  if (auto bits = s.optional_section("control_bits")) {
    set_if(bits->optional_integer("enable", 0, 15), map.control_bits.enable);
    set_if(bits->optional_integer("reset_alarm", 0, 15), map.control_bits.reset_alarm);
    set_if(bits->optional_integer("torque_mode", 0, 15), map.control_bits.torque_mode);
    bits->finish();
  }
  if (auto bits = s.optional_section("status_bits")) {
    const std::pair<const char*, int*> named[] = {
        {"output_on", &map.status_bits.output_on},
        {"alarm", &map.status_bits.alarm},
        {"over_temperature", &map.status_bits.over_temperature},
        {"watchdog_tripped", &map.status_bits.watchdog_tripped},
        {"coil_open", &map.status_bits.coil_open},
        {"at_setpoint", &map.status_bits.at_setpoint}};
    for (const auto& [name, bit] : named) set_if(bits->optional_integer(name, 0, 15), *bit);
    bits->finish();
  }
  if (auto texts = s.optional_section("alarm_texts")) {
    map.alarm_texts.clear();
    for (const std::string& code : texts->keys()) {
      long long value = -1;
      if (!YAML::convert<long long>::decode(YAML::Node(code), value) || value < 0 ||
          value > 65535) {
        texts->fail(code, code, "an alarm code in [0, 65535] as the key");
      }
      map.alarm_texts[static_cast<int>(value)] = texts->text(code);
    }
    texts->finish();
  }
  s.finish();
}

void read_link(YamlSection& s, BrakeClientConfig& cfg) {
  auto& ep = cfg.link.endpoint;
  if (const auto text = s.optional_text("endpoint")) {
    try {
      ep = parse_modbus_endpoint(*text);
    } catch (const std::invalid_argument& e) {
      s.fail("endpoint", *text,
             "tcp:HOST:PORT or rtu:DEVICE[:BAUD...] (" + std::string(e.what()) + ")");
    }
  }
  if (const auto t = s.optional_choice("transport", {"tcp", "rtu"})) {
    ep.transport = *t == "tcp" ? Transport::tcp : Transport::rtu;
  }
  if (const auto v = s.optional_text("host")) ep.host = *v;
  set_if(s.optional_integer("port", 0, 65535), ep.port);
  if (const auto v = s.optional_text("device")) ep.device = *v;
  set_if(s.optional_integer("baud", 1, 4000000), ep.baud);
  if (const auto v = s.optional_choice("parity", {"N", "E", "O"})) ep.parity = (*v)[0];
  set_if(s.optional_integer("data_bits", 5, 8), ep.data_bits);
  set_if(s.optional_integer("stop_bits", 1, 2), ep.stop_bits);
  set_if(s.optional_integer("unit_id", 0, 255), cfg.link.unit_id);
  if (ep.transport == Transport::rtu && ep.device.empty()) {
    s.fail("device", "", "a serial device path for the rtu transport");
  }
  s.finish();
}

}  // namespace

BrakeClientConfig read_brake_config(YamlSection& s) {
  BrakeClientConfig cfg;
  if (auto link = s.optional_section("link")) read_link(*link, cfg);
  if (auto t = s.optional_section("timeouts")) {
    set_ms_if(t->optional_integer("response_ms", 1, 60000), cfg.link.response_timeout);
    set_ms_if(t->optional_integer("byte_ms", 1, 60000), cfg.link.byte_timeout);
    // A safety timeout: a link silent for a minute is lost (safety.modbus_link_timeout agrees).
    set_ms_if(t->optional_integer("link_loss_ms", 1, 60000), cfg.link.link_loss_timeout);
    t->finish();
  }
  if (auto r = s.optional_section("reconnect")) {
    set_ms_if(r->optional_integer("initial_backoff_ms", 1, 600000),
              cfg.link.reconnect_initial_backoff);
    set_ms_if(r->optional_integer("max_backoff_ms", 1, 600000), cfg.link.reconnect_max_backoff);
    if (cfg.link.reconnect_max_backoff < cfg.link.reconnect_initial_backoff) {
      r->fail("max_backoff_ms", std::to_string(cfg.link.reconnect_max_backoff.count()),
              "at least reconnect.initial_backoff_ms (" +
                  std::to_string(cfg.link.reconnect_initial_backoff.count()) + ")");
    }
    r->finish();
  }
  if (auto h = s.optional_section("heartbeat")) {
    set_ms_if(h->optional_integer("period_ms", 1, 60000), cfg.heartbeat.period);
    set_ms_if(h->optional_integer("watchdog_ms", 0, 65535), cfg.heartbeat.watchdog_timeout);
    if (cfg.heartbeat.watchdog_timeout.count() != 0 &&
        cfg.heartbeat.watchdog_timeout <= cfg.heartbeat.period) {
      h->fail("watchdog_ms", std::to_string(cfg.heartbeat.watchdog_timeout.count()),
              "0 (off) or longer than heartbeat.period_ms (" +
                  std::to_string(cfg.heartbeat.period.count()) + ")");
    }
    h->finish();
  }
  if (auto l = s.optional_section("limits")) {
    cfg.limits.max_current_a = l->number_or("max_current_a", 0.0, 1000.0, cfg.limits.max_current_a);
    cfg.limits.max_torque_nm = l->number_or("max_torque_nm", 0.0, 1e6, cfg.limits.max_torque_nm);
    cfg.limits.max_ramp_per_s = l->number_or("max_ramp_per_s", 0.0, 1e9, cfg.limits.max_ramp_per_s);
    l->finish();
  }
  if (auto m = s.optional_section("map")) read_map(*m, cfg.map);
  s.finish();
  return cfg;
}

BrakeClientConfig load_brake_config(const YAML::Node& node) {
  if (!node || node.IsNull()) return {};
  try {
    YamlSection s(node, "", "brake config");
    return read_brake_config(s);
  } catch (const strict_yaml::RefusedConfig& e) {
    throw BrakeConfigError(e);
  }
}

BrakeClientConfig load_brake_config_file(const std::filesystem::path& path) {
  try {
    const std::string source = path.string();
    YamlSection root = strict_yaml::document_section(
        strict_yaml::parse_strict_yaml(strict_yaml::read_config_file(path), source), source,
        "a mapping of brake settings");
    // A file with a `brake:` section (a bench config) is read for that section alone.
    if (!root.has("brake")) return read_brake_config(root);
    YamlSection brake = root.section("brake");
    return read_brake_config(brake);
  } catch (const BrakeConfigError&) {
    throw;
  } catch (const strict_yaml::RefusedConfig& e) {
    throw BrakeConfigError(e);
  }
}

}  // namespace wavebench::modbus
