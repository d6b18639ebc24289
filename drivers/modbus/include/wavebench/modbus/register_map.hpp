#pragma once
// Where the brake controller keeps each quantity. Real powder-brake controllers differ, so every
// address, table, type, scale and the float word order comes from config; the defaults are the
// map of the simulated controller (bench.md §3).

#include <cstdint>
#include <map>
#include <string>

namespace wavebench::modbus {

enum class RegisterTable { holding, input };
enum class DataType { uint16, int16, uint32, int32, float32 };
// Order of the four bytes of a 32-bit value on the wire, A = most significant byte.
enum class WordOrder { abcd, cdab, badc, dcba };

// engineering value = raw * scale + offset
struct RegisterSpec {
  RegisterTable table = RegisterTable::holding;
  int address = 0;
  DataType type = DataType::uint16;
  double scale = 1.0;
  double offset = 0.0;
};

int register_count(DataType type);

struct ControlBits {
  int enable = 0;
  int reset_alarm = 1;
  int torque_mode = 2;
};

struct StatusBits {
  int output_on = 0;
  int alarm = 1;
  int over_temperature = 2;
  int watchdog_tripped = 3;
  int coil_open = 4;
  int at_setpoint = 5;
};

struct BrakeRegisterMap {
  WordOrder word_order = WordOrder::abcd;
  RegisterSpec control{RegisterTable::holding, 0, DataType::uint16};
  RegisterSpec watchdog_timeout_ms{RegisterTable::holding, 1, DataType::uint16};
  RegisterSpec heartbeat{RegisterTable::holding, 2, DataType::uint16};
  RegisterSpec setpoint{RegisterTable::holding, 10, DataType::float32};
  RegisterSpec setpoint_ramp{RegisterTable::holding, 12, DataType::float32};
  RegisterSpec status{RegisterTable::input, 0, DataType::uint16};
  RegisterSpec coil_current{RegisterTable::input, 10, DataType::float32};
  RegisterSpec torque{RegisterTable::input, 12, DataType::float32};
  RegisterSpec temperature{RegisterTable::input, 14, DataType::float32};
  RegisterSpec slip_power{RegisterTable::input, 16, DataType::float32};
  RegisterSpec alarm_code{RegisterTable::input, 20, DataType::uint16};
  ControlBits control_bits;
  StatusBits status_bits;
  // Alarm code -> text; codes not listed come out as "alarm code N".
  std::map<int, std::string> alarm_texts{
      {1, "coil over-temperature"}, {2, "watchdog timeout (no heartbeat)"}, {3, "coil open"}};
};

std::string to_string(RegisterTable table);
std::string to_string(DataType type);
std::string to_string(WordOrder order);

}  // namespace wavebench::modbus
