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
#include <vector>

#include "wavebench/bench/bench_description.hpp"
#include "wavebench/bench/channel_device.hpp"
#include "wavebench/bench/drive_unit_choice.hpp"
#include "wavebench/canopen/eds.hpp"
#include "wavebench/canopen/torque_sensor.hpp"
#include "wavebench/modbus/brake_config.hpp"

namespace wavebench::simdevices {
struct SimulatedBenchConfig;
}

namespace wavebench::bench {

enum class BenchClockKind { kReal, kSimulated };

// Node guarding (CiA 301 §7.2.8.3.2.1) of a device without a heartbeat producer: the bench
// guards a node whose 0x1017 does not exist or is read-only, and the nodes named here whatever
// they have. Loss: no answer for guard time x life time factor (bounded by
// safety.heartbeat_timeout), or a toggle that does not alternate.
struct NodeGuardingSettings {
  double guard_time_s = 0.1;          // written to 0x100C, and the request period
  std::uint8_t life_time_factor = 3;  // written to 0x100D
  std::vector<std::uint8_t> nodes;    // guarded even when they have 0x1017
};

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
  // Bench time after a trip's quick stop for the drive's statusword to show it; NMT stop after.
  double quick_stop_timeout_s = 0.05;
  NodeGuardingSettings node_guarding;  // `can.node_guarding`
};

// 0x1018 as the config expects it (`identity:` of a device); unset sub-indices are not compared.
struct ExpectedIdentity {
  std::optional<std::uint32_t> vendor_id;
  std::optional<std::uint32_t> product_code;
  std::optional<std::uint32_t> revision;
  std::optional<std::uint32_t> serial_number;
};

// What a CANopen device of the bench is expected to be: its EDS (`eds:`, relative to the config
// file; every object the bench uses is checked against it before connecting) and its identity.
struct NodeExpectations {
  std::filesystem::path eds_path;           // empty: none named
  std::shared_ptr<const canopen::Eds> eds;  // read at config load
  ExpectedIdentity identity;
};

struct DriveSettings {
  std::uint32_t counts_per_revolution = 131072;  // motor encoder increments per input turn
  double profile_acceleration_rad_s2 = 0;        // 0: the drive's own 0x6083/0x6084
  double target_settle_s = 0.0;                  // extra wait after target reached
  NodeExpectations expect;
  // The drive's units (drive_unit_choice.hpp); counts of the motor encoder by default.
  DriveUnitChoice position_unit{DriveUnitChoice::Kind::kCounts, 0, "counts"};
  DriveUnitChoice velocity_unit{DriveUnitChoice::Kind::kCounts, 0, "counts/s"};
  DriveUnitChoice acceleration_unit{DriveUnitChoice::Kind::kCounts, 0, "counts/s²"};
  // N·m per unit of torque actual 0x6077; unset: per mille of the rated torque 0x6076 (mN·m),
  // read at connect.
  std::optional<double> torque_actual_nm_per_unit;
};

struct EncoderSettings {
  std::optional<std::uint32_t> counts_per_turn;  // unset: read 0x6501
  std::optional<std::uint32_t> turns;            // unset: read 0x6502
  double noise_rad = 0;                          // for the twin's residual floor
  NodeExpectations expect;
};

struct TorqueSensorSettings {
  canopen::TorqueSensorConfig sensor{0x6130, 1, canopen::ValueType::i32, 1e-3, 0.0};
  double noise_nm = 0;
  NodeExpectations expect;
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
  // A simulated device sits at can.nodes unless simbench names its node_id: a miswired bench
  // (the commissioning check's wrong-node case).
  std::optional<std::uint8_t> drive_node, encoder_node, torque_node;
  // false: no simulated brake controller; the bench talks to brake.link as configured (an
  // external controller, or nobody: the commissioning check's unreachable-brake case).
  bool brake_server = true;
};

struct BenchConfig {
  BenchDescription description;
  BenchClockKind clock = BenchClockKind::kSimulated;
  CanSettings can;
  DriveSettings drive;
  EncoderSettings encoder;
  TorqueSensorSettings torque_sensor;
  modbus::BrakeClientConfig brake;
  // Further CANopen devices, each recorded as an extra channel (`devices:`), in config order.
  std::vector<ChannelDeviceSettings> devices;
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
// "simulated" (or its old name "sim") -> the default simulated bench; anything else is a file path.
BenchConfig bench_config_from_argument(const std::string& sim_or_path);

}  // namespace wavebench::bench
