#pragma once
// The brake controller's status word and alarm code, decoded.

#include <cstdint>
#include <string>

#include "wavebench/modbus/register_map.hpp"

namespace wavebench::modbus {

struct BrakeStatus {
  uint16_t raw = 0;
  bool output_on = false;
  bool alarm = false;
  bool over_temperature = false;
  bool watchdog_tripped = false;
  bool coil_open = false;
  bool at_setpoint = false;
};

BrakeStatus decode_status(uint16_t word, const StatusBits& bits);
// e.g. "alarm: coil over-temperature; over-temperature" or "no alarm".
std::string describe_alarms(const BrakeStatus& status, int alarm_code, const BrakeRegisterMap& map);
std::string describe_status(const BrakeStatus& status);

}  // namespace wavebench::modbus
