#pragma once
// Where a Modbus peer is: `tcp:HOST:PORT` or `rtu:DEVICE[:BAUD[:PARITY[:DATABITS[:STOPBITS]]]]`.

#include <string>

namespace wavebench::modbus {

enum class Transport { tcp, rtu };

struct ModbusEndpoint {
  Transport transport = Transport::tcp;
  std::string host = "127.0.0.1";
  int port = 1502;
  std::string device;
  int baud = 19200;
  char parity = 'N';  // N, E or O
  int data_bits = 8;
  int stop_bits = 1;
};

// Throws std::invalid_argument naming the text and what was expected.
ModbusEndpoint parse_modbus_endpoint(const std::string& text);
std::string to_string(const ModbusEndpoint& endpoint);

}  // namespace wavebench::modbus
