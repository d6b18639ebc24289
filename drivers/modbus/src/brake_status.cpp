#include "wavebench/modbus/brake_status.hpp"

namespace wavebench::modbus {

namespace {
bool bit(uint16_t word, int n) {
  return ((word >> n) & 1u) != 0;
}
}  // namespace

BrakeStatus decode_status(uint16_t word, const StatusBits& bits) {
  BrakeStatus s;
  s.raw = word;
  s.output_on = bit(word, bits.output_on);
  s.alarm = bit(word, bits.alarm);
  s.over_temperature = bit(word, bits.over_temperature);
  s.watchdog_tripped = bit(word, bits.watchdog_tripped);
  s.coil_open = bit(word, bits.coil_open);
  s.at_setpoint = bit(word, bits.at_setpoint);
  return s;
}

std::string describe_alarms(const BrakeStatus& status, int alarm_code,
                            const BrakeRegisterMap& map) {
  std::string text;
  auto add = [&text](const std::string& part) { text += (text.empty() ? "" : "; ") + part; };
  if (alarm_code != 0) {
    const auto it = map.alarm_texts.find(alarm_code);
    add("alarm " + std::to_string(alarm_code) + ": " +
        (it != map.alarm_texts.end() ? it->second : "unknown alarm code"));
  } else if (status.alarm) {
    add("alarm (no code)");
  }
  if (status.over_temperature) add("over-temperature");
  if (status.watchdog_tripped) add("watchdog tripped");
  if (status.coil_open) add("coil open");
  return text.empty() ? "no alarm" : text;
}

std::string describe_status(const BrakeStatus& status) {
  std::string text = status.output_on ? "output on" : "output off";
  if (status.at_setpoint) text += ", at setpoint";
  if (status.alarm) text += ", ALARM";
  return text;
}

}  // namespace wavebench::modbus
