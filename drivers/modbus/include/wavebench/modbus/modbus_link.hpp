#pragma once
// One Modbus TCP or RTU connection on one libmodbus context. libmodbus contexts are not
// thread-safe: one thread at a time (BrakeClient hands out turns); connected(),
// transactions() and connections() may be read from any thread.
//
// Requests go out through libmodbus (framing, CRC, timeouts); every reply is checked here for
// transaction id, unit id, function code and length, because libmodbus does not check the unit
// id of a TCP reply and a wrong-unit reply must not be taken for the device's answer.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <vector>

#include "wavebench/modbus/brake_config.hpp"
#include "wavebench/modbus/modbus_error.hpp"
#include "wavebench/modbus/register_map.hpp"

struct _modbus;

namespace wavebench::modbus {

class ModbusLink {
 public:
  explicit ModbusLink(BrakeLinkConfig config);
  ~ModbusLink();
  ModbusLink(const ModbusLink&) = delete;
  ModbusLink& operator=(const ModbusLink&) = delete;

  // Throws ModbusError(not_connected) naming the endpoint and the system's reason.
  void connect();
  void close() noexcept;
  bool connected() const noexcept { return open_.load(std::memory_order_acquire); }

  std::vector<uint16_t> read_registers(RegisterTable table, int address, int count);
  // One register with function 6, more with function 16.
  void write_registers(int address, const std::vector<uint16_t>& values);

  const BrakeLinkConfig& config() const noexcept { return config_; }
  uint64_t transactions() const noexcept { return transactions_.load(std::memory_order_relaxed); }
  // Connections opened so far: a change means a new connection (maybe a restarted device).
  uint64_t connections() const noexcept { return connections_.load(std::memory_order_acquire); }

 private:
  std::vector<uint8_t> transact(const std::vector<uint8_t>& pdu);
  [[noreturn]] void fail_transport(int err, const char* during);
  void unlock(std::uint64_t secret);

  BrakeLinkConfig config_;
  _modbus* ctx_ = nullptr;
  uint16_t last_tid_ = 0;  // MBAP transaction id of the last TCP request
  bool flush_before_next_ = false;
  // RTU has no transaction id: after a timeout, wait out the late reply before asking again.
  std::chrono::steady_clock::time_point quiet_until_{};
  std::atomic<uint64_t> transactions_{0};
  std::atomic<uint64_t> connections_{0};
  std::atomic<bool> open_{false};
};

}  // namespace wavebench::modbus
