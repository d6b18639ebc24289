#pragma once
// A failed Modbus transaction, classified so callers can tell a slow peer from a refusal.

#include <stdexcept>
#include <string>

namespace wavebench::modbus {

enum class ModbusErrorKind {
  not_connected,  // no link (connect failed, or waiting for the reconnect backoff)
  timeout,        // no (complete) reply within the response/byte timeout
  connection,     // the link broke (peer closed, I/O error)
  exception,      // the peer answered with a Modbus exception response
  bad_reply,      // malformed reply: wrong transaction/function/length, bad CRC, garbage
  wrong_unit,     // a reply came from another unit id
  invalid_argument,
};

class ModbusError : public std::runtime_error {
 public:
  ModbusError(ModbusErrorKind kind, const std::string& what, int exception_code = 0)
      : std::runtime_error(what), kind_(kind), exception_code_(exception_code) {}
  ModbusErrorKind kind() const noexcept { return kind_; }
  int exception_code() const noexcept { return exception_code_; }

 private:
  ModbusErrorKind kind_;
  int exception_code_;
};

std::string to_string(ModbusErrorKind kind);
// Text of a Modbus exception code (1 illegal function ... 11 gateway target failed).
std::string exception_text(int code);

}  // namespace wavebench::modbus
