#include "wavebench/modbus/modbus_endpoint.hpp"

#include <charconv>
#include <stdexcept>
#include <vector>

namespace wavebench::modbus {

namespace {

int parse_int(const std::string& field, const std::string& text, const char* what, int lo, int hi) {
  int v = 0;
  const auto* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, v);
  if (ec != std::errc{} || ptr != end || v < lo || v > hi) {
    throw std::invalid_argument("modbus endpoint '" + text + "': " + what + " '" + field +
                                "' is not an integer in [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "]");
  }
  return v;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (;;) {
    const size_t pos = s.find(sep, start);
    parts.push_back(s.substr(start, pos - start));
    if (pos == std::string::npos) break;
    start = pos + 1;
  }
  return parts;
}

}  // namespace

ModbusEndpoint parse_modbus_endpoint(const std::string& text) {
  ModbusEndpoint ep;
  if (text.rfind("tcp:", 0) == 0) {
    ep.transport = Transport::tcp;
    const std::string rest = text.substr(4);
    const size_t colon = rest.rfind(':');
    if (colon == std::string::npos || colon == 0) {
      throw std::invalid_argument("modbus endpoint '" + text + "': expected tcp:HOST:PORT");
    }
    ep.host = rest.substr(0, colon);
    ep.port = parse_int(rest.substr(colon + 1), text, "port", 0, 65535);
    return ep;
  }
  if (text.rfind("rtu:", 0) == 0) {
    ep.transport = Transport::rtu;
    const auto parts = split(text.substr(4), ':');
    if (parts.empty() || parts[0].empty()) {
      throw std::invalid_argument("modbus endpoint '" + text +
                                  "': expected rtu:DEVICE[:BAUD[:PARITY[:DATABITS[:STOPBITS]]]]");
    }
    ep.device = parts[0];
    if (parts.size() > 1) ep.baud = parse_int(parts[1], text, "baud rate", 1, 4000000);
    if (parts.size() > 2) {
      if (parts[2].size() != 1 || std::string("NEO").find(parts[2][0]) == std::string::npos) {
        throw std::invalid_argument("modbus endpoint '" + text + "': parity '" + parts[2] +
                                    "' is not one of N, E, O");
      }
      ep.parity = parts[2][0];
    }
    if (parts.size() > 3) ep.data_bits = parse_int(parts[3], text, "data bits", 5, 8);
    if (parts.size() > 4) ep.stop_bits = parse_int(parts[4], text, "stop bits", 1, 2);
    if (parts.size() > 5) {
      throw std::invalid_argument("modbus endpoint '" + text + "': too many fields");
    }
    return ep;
  }
  throw std::invalid_argument("modbus endpoint '" + text +
                              "': expected tcp:HOST:PORT or rtu:DEVICE[:BAUD...]");
}

std::string to_string(const ModbusEndpoint& ep) {
  if (ep.transport == Transport::tcp) return "tcp:" + ep.host + ":" + std::to_string(ep.port);
  return "rtu:" + ep.device + ":" + std::to_string(ep.baud) + ":" + std::string(1, ep.parity) +
         ":" + std::to_string(ep.data_bits) + ":" + std::to_string(ep.stop_bits);
}

}  // namespace wavebench::modbus
