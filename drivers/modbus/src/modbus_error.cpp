#include "wavebench/modbus/modbus_error.hpp"

namespace wavebench::modbus {

std::string to_string(ModbusErrorKind kind) {
  switch (kind) {
    case ModbusErrorKind::not_connected:
      return "not connected";
    case ModbusErrorKind::timeout:
      return "timeout";
    case ModbusErrorKind::connection:
      return "connection lost";
    case ModbusErrorKind::exception:
      return "exception response";
    case ModbusErrorKind::bad_reply:
      return "malformed reply";
    case ModbusErrorKind::wrong_unit:
      return "reply from wrong unit id";
    case ModbusErrorKind::invalid_argument:
      return "invalid argument";
  }
  return "?";
}

std::string exception_text(int code) {
  switch (code) {
    case 1:
      return "illegal function";
    case 2:
      return "illegal data address";
    case 3:
      return "illegal data value";
    case 4:
      return "server device failure";
    case 5:
      return "acknowledge";
    case 6:
      return "server device busy";
    case 7:
      return "negative acknowledge";
    case 8:
      return "memory parity error";
    case 10:
      return "gateway path unavailable";
    case 11:
      return "gateway target device failed to respond";
    default:
      return "unknown exception code " + std::to_string(code);
  }
}

}  // namespace wavebench::modbus
