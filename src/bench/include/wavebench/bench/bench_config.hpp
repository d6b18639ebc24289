#pragma once
// A bench config (configs/benches/*.yaml): the devices, their addresses and scaling, the SYNC
// period, the clock, the safety limits (bench.md §7), the twin beside the bench and, for the
// simulated bench, the simulated devices and the unit's "true" gear. Quantities may carry units
// ("1 ms", "3000 rpm", "0.5 arcsec"); everything here is SI.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "wavebench/bench/bench_description.hpp"
#include "wavebench/canopen/torque_sensor.hpp"
#include "wavebench/modbus/brake_config.hpp"

namespace wavebench::simdevices {
struct SimulatedBenchConfig;
}

namespace wavebench::bench {

enum class BenchClockKind { kReal, kSimulated };

struct CanSettings {
  std::string interface = "inproc";  // "inproc": the in-process simulated bench's virtual bus
  double bitrate = 1e6;              // [bit/s] for the bus-load estimate
  double sdo_timeout_s = 0.5;
  double heartbeat_producer_s = 0.1;  // written to every node's 0x1017
  std::uint8_t drive_node = 1;
  std::uint8_t encoder_node = 3;
  std::uint8_t torque_node = 4;
  double bus_load_warning = 0.8;  // fraction of the bit rate
  double cycle_timeout_s = 0.05;  // simulated clock: real time to wait for a cycle's PDOs
};

struct DriveSettings {
  std::uint32_t counts_per_revolution = 131072;  // motor encoder increments per input turn
  double profile_acceleration_rad_s2 = 0;        // 0: the drive's own 0x6083/0x6084
  double target_settle_s = 0.0;                  // extra wait after target reached
};

struct EncoderSettings {
  std::optional<std::uint32_t> counts_per_turn;  // unset: read 0x6501
  std::optional<std::uint32_t> turns;            // unset: read 0x6502
  double noise_rad = 0;                          // for the twin's residual floor
};

struct TorqueSensorSettings {
  canopen::TorqueSensorConfig sensor{0x6130, 1, canopen::ValueType::i32, 1e-3, 0.0};
  double noise_nm = 0;
};

// How the simulated unit's "true" gear differs from the case it starts from, so that the twin
// (nominal) and the simulated unit (true) are not the same gear.
struct TrueGearVariation {
  double te_amplitude_scale = 1.0;
  double te_phase_shift_rad = 0;
  double stiffness_scale = 1.0;
  std::optional<double> backlash_rad;
};

struct SimulatedSettings {
  std::filesystem::path true_gear_case;  // a twin case; its gear, varied, is the unit's truth
  TrueGearVariation variation;
  // The `simbench:` section as the simulator reads it (node ids, noise, ...; clock set by the
  // bench factory), null without one: the simulator's defaults. Behind a pointer so that the
  // production bench's headers do not include the simulator.
  std::shared_ptr<const simdevices::SimulatedBenchConfig> devices;
};

struct BenchConfig {
  BenchDescription description;
  BenchClockKind clock = BenchClockKind::kSimulated;
  CanSettings can;
  DriveSettings drive;
  EncoderSettings encoder;
  TorqueSensorSettings torque_sensor;
  modbus::BrakeClientConfig brake;
  // The in-process simulated bench serves its brake on loopback with an ephemeral port and
  // sets brake.link.endpoint itself.
  std::optional<SimulatedSettings> simulated;
  std::string source;  // the file it came from, or "<built-in sim>"
  std::string text;    // the YAML as read (runs copy and hash it)

  bool in_process() const { return can.interface == "inproc"; }
};

// Throws config::ConfigError naming the key, the value and what was expected. Relative paths
// in the file resolve against the file's folder.
BenchConfig load_bench_config(const std::filesystem::path& path);
BenchConfig parse_bench_config(const std::string& yaml_text, const std::filesystem::path& base_dir,
                               const std::string& source = "<string>");
// configs/benches/sim.yaml (the default where no hardware is named) of $WAVEBENCH_CONFIG_DIR,
// else of the source tree.
BenchConfig default_simulated_bench_config();
// "sim" -> the default simulated bench; anything else is a file path.
BenchConfig bench_config_from_argument(const std::string& sim_or_path);

}  // namespace wavebench::bench
