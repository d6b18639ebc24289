#pragma once
// Configuration of the brake client: where the controller is, how long to wait for it, how to
// reconnect, the heartbeat, the safety limits and the register map. Loaded from YAML
// (configs/bench/brake-default.yaml shows every key with its default).

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "wavebench/modbus/modbus_endpoint.hpp"
#include "wavebench/modbus/register_map.hpp"
#include "wavebench/strict_yaml/yaml_section.hpp"

namespace wavebench::modbus {

struct BrakeLinkConfig {
  ModbusEndpoint endpoint;
  int unit_id = 1;
  std::chrono::milliseconds response_timeout{500};
  std::chrono::milliseconds byte_timeout{100};
  // No successful transaction for this long: the link is lost (safety event).
  std::chrono::milliseconds link_loss_timeout{1000};
  std::chrono::milliseconds reconnect_initial_backoff{100};
  std::chrono::milliseconds reconnect_max_backoff{5000};
  // A controller that takes writes only after a shared secret (the simulated controller of the
  // in-process bench): written, high word first, to the four holding registers at
  // `unlock_address` on every new connection. Unset: nothing written (a real controller).
  std::optional<std::uint64_t> unlock_secret;
  int unlock_address = 24;
};

struct BrakeHeartbeatConfig {
  std::chrono::milliseconds period{100};
  // Written to the controller's watchdog register when the supervisor starts (0 = off).
  std::chrono::milliseconds watchdog_timeout{500};
};

struct BrakeLimits {
  double max_current_a = 2.0;
  double max_torque_nm = 100.0;
  double max_ramp_per_s = 1000.0;
};

struct BrakeClientConfig {
  BrakeLinkConfig link;
  BrakeHeartbeatConfig heartbeat;
  BrakeLimits limits;
  BrakeRegisterMap map;
};

// Bad config: the one refusal of every loader (source, key path, value, what was expected).
class BrakeConfigError : public strict_yaml::RefusedConfig {
 public:
  explicit BrakeConfigError(const strict_yaml::RefusedConfig& refusal)
      : strict_yaml::RefusedConfig(refusal) {}
};

// The brake section (keys link, timeouts, reconnect, heartbeat, limits, map); missing keys keep
// their defaults, unknown keys are refused (strict_yaml::RefusedConfig, with the section's key
// path, so a bench config names "brake.link.port").
BrakeClientConfig read_brake_config(strict_yaml::YamlSection& section);
// The same for a node read elsewhere (source "brake config"); null = all defaults. Throws
// BrakeConfigError.
BrakeClientConfig load_brake_config(const YAML::Node& node);
// The file's top-level `brake:` section, or the whole file if it has none.
BrakeClientConfig load_brake_config_file(const std::filesystem::path& path);

}  // namespace wavebench::modbus
