#include "wavebench/modbus/brake_config.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

namespace wavebench::modbus {
namespace {

std::string error_of(const std::string& yaml) {
  try {
    load_brake_config(YAML::Load(yaml));
  } catch (const BrakeConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(BrakeConfig, DefaultFileMatchesBuiltInDefaults) {
  const auto cfg = load_brake_config_file(std::string(WAVEBENCH_SOURCE_DIR) +
                                          "/configs/bench/brake-default.yaml");
  const BrakeClientConfig def;
  EXPECT_EQ(cfg.link.endpoint.transport, Transport::tcp);
  EXPECT_EQ(cfg.link.endpoint.host, "127.0.0.1");
  EXPECT_EQ(cfg.link.endpoint.port, 1502);
  EXPECT_EQ(cfg.link.unit_id, 1);
  EXPECT_EQ(cfg.link.response_timeout, def.link.response_timeout);
  EXPECT_EQ(cfg.link.byte_timeout, def.link.byte_timeout);
  EXPECT_EQ(cfg.link.link_loss_timeout, def.link.link_loss_timeout);
  EXPECT_EQ(cfg.heartbeat.period, def.heartbeat.period);
  EXPECT_EQ(cfg.heartbeat.watchdog_timeout, def.heartbeat.watchdog_timeout);
  EXPECT_EQ(cfg.map.word_order, WordOrder::abcd);
  EXPECT_EQ(cfg.map.setpoint.address, 10);
  EXPECT_EQ(cfg.map.setpoint.type, DataType::float32);
  EXPECT_EQ(cfg.map.slip_power.address, 16);
  EXPECT_EQ(cfg.map.slip_power.table, RegisterTable::input);
  EXPECT_EQ(cfg.map.alarm_code.address, 20);
  EXPECT_EQ(cfg.map.status_bits.at_setpoint, 5);
  EXPECT_EQ(cfg.map.alarm_texts.at(1), "coil over-temperature");
}

TEST(BrakeConfig, OverridesMapAndLink) {
  const auto cfg = load_brake_config(YAML::Load(R"(
link: {endpoint: "rtu:/dev/ttyS3:9600:E:8:1", unit_id: 7}
timeouts: {response_ms: 250, byte_ms: 20}
map:
  word_order: cdab
  torque: {table: holding, address: 100, type: int16, scale: 0.1}
)"));
  EXPECT_EQ(cfg.link.endpoint.transport, Transport::rtu);
  EXPECT_EQ(cfg.link.endpoint.device, "/dev/ttyS3");
  EXPECT_EQ(cfg.link.endpoint.baud, 9600);
  EXPECT_EQ(cfg.link.endpoint.parity, 'E');
  EXPECT_EQ(cfg.link.unit_id, 7);
  EXPECT_EQ(cfg.link.response_timeout.count(), 250);
  EXPECT_EQ(cfg.map.word_order, WordOrder::cdab);
  EXPECT_EQ(cfg.map.torque.table, RegisterTable::holding);
  EXPECT_EQ(cfg.map.torque.address, 100);
  EXPECT_EQ(cfg.map.torque.type, DataType::int16);
  EXPECT_DOUBLE_EQ(cfg.map.torque.scale, 0.1);
  EXPECT_EQ(cfg.map.setpoint.address, 10);  // untouched keys keep defaults
}

TEST(BrakeConfig, ErrorsNameKeyValueAndExpectation) {
  std::string e = error_of("timeouts: {response_ms: fast}");
  EXPECT_NE(e.find("timeouts.response_ms"), std::string::npos) << e;
  EXPECT_NE(e.find("'fast'"), std::string::npos) << e;
  EXPECT_NE(e.find("integer"), std::string::npos) << e;

  e = error_of("map: {word_order: xyzw}");
  EXPECT_NE(e.find("map.word_order"), std::string::npos) << e;
  EXPECT_NE(e.find("'xyzw'"), std::string::npos) << e;
  EXPECT_NE(e.find("abcd"), std::string::npos) << e;

  e = error_of("map: {setpoint: {type: double}}");
  EXPECT_NE(e.find("map.setpoint.type"), std::string::npos) << e;
  EXPECT_NE(e.find("float32"), std::string::npos) << e;

  e = error_of("map: {setpoint: {table: input}}");
  EXPECT_NE(e.find("map.setpoint.table"), std::string::npos) << e;

  e = error_of("link: {port: 70000}");
  EXPECT_NE(e.find("link.port"), std::string::npos) << e;
  EXPECT_NE(e.find("70000"), std::string::npos) << e;

  e = error_of("link: {unit: 3}");
  EXPECT_NE(e.find("link.unit"), std::string::npos) << e;
  EXPECT_NE(e.find("no such key"), std::string::npos) << e;

  e = error_of("heartbeat: {period_ms: 500, watchdog_ms: 200}");
  EXPECT_NE(e.find("heartbeat.watchdog_ms"), std::string::npos) << e;

  e = error_of("link: {endpoint: \"udp:1.2.3.4:5\"}");
  EXPECT_NE(e.find("link.endpoint"), std::string::npos) << e;
}

TEST(ModbusEndpoint, Parses) {
  const auto tcp = parse_modbus_endpoint("tcp:127.0.0.1:1502");
  EXPECT_EQ(tcp.transport, Transport::tcp);
  EXPECT_EQ(tcp.host, "127.0.0.1");
  EXPECT_EQ(tcp.port, 1502);
  const auto rtu = parse_modbus_endpoint("rtu:/dev/pts/4");
  EXPECT_EQ(rtu.transport, Transport::rtu);
  EXPECT_EQ(rtu.device, "/dev/pts/4");
  EXPECT_EQ(rtu.baud, 19200);
  const auto rtu2 = parse_modbus_endpoint("rtu:/dev/ttyUSB0:115200:O:7:2");
  EXPECT_EQ(rtu2.baud, 115200);
  EXPECT_EQ(rtu2.parity, 'O');
  EXPECT_EQ(rtu2.data_bits, 7);
  EXPECT_EQ(rtu2.stop_bits, 2);
  EXPECT_THROW(parse_modbus_endpoint("tcp:host"), std::invalid_argument);
  EXPECT_THROW(parse_modbus_endpoint("tcp:host:99999"), std::invalid_argument);
  EXPECT_THROW(parse_modbus_endpoint("rtu:/dev/x:9600:Q"), std::invalid_argument);
  EXPECT_THROW(parse_modbus_endpoint("serial:/dev/x"), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::modbus
