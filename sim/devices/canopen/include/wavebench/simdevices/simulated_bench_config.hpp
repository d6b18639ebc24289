#pragma once
// The simulated bench's device settings from YAML (a `simbench:` section; every key optional):
//
//   simbench:
//     clock: realtime            # realtime | sync | manual
//     sync_period_us: 1000
//     brake_torque_nm: 0
//     drive:   {node_id: 1, counts_per_revolution: 131072, rated_torque_nm: 1.3,
//               max_torque_permille: 3000, max_motor_speed_rpm: 3000, position_gain: 120,
//               velocity_gain: 0.08, velocity_integral_time_s: 0.01, control_period_us: 250,
//               quick_stop_option: 6, following_error_window: 65536,
//               following_error_timeout_ms: 50, serial_number: 4097,
//               velocity_unit: counts/s,        # counts/s | rpm | "0.1 rpm" | factor_group
//               si_unit_objects: false,         # true: 0x60A8/0x60A9 state the units
//               factor_group: {position_encoder_resolution: [131072, 1],   # 0x608F
//                              velocity_encoder_resolution: [131072, 1],   # 0x6090
//                              gear_ratio: [1, 1],                         # 0x6091
//                              feed_constant: [131072, 1]},                # 0x6092
//               absent_objects: [],             # optional objects lacking: "0x60F4", "0x6077",
//                                               # "0x603F" (error code), "0x1018:4" (serial)
//               fixed_tpdo_mapping: {tpdo1: ["0x6064:0/32", "0x6041:0/16"],
//                                    tpdo2: ["0x606C:0/32"]}}   # absent: remappable TPDOs
//     encoder: {node_id: 3, resolution: 1048576, revolutions: 2048, noise_arcsec: 0.5, seed: 3}
//     torque_sensor: {node_id: 4, object: "0x6130:1", type: i32, scale: 0.001,
//                     noise_nm: 0.02, offset_nm: 0, seed: 4}
//     input_encoder: {node_id: 5, resolution: 1048576, revolutions: 1, noise_arcsec: 0.5,
//                     seed: 5}   # absent: no input-side encoder (seed 004's bench has one)
//
// Drive units (issue #9): with `velocity_unit` rpm or 0.1 rpm the drive's velocity objects
// (0x606C, 0x60FF, 0x6081, 0x607F, 0x606D, 0x606F) are in that unit and its accelerations
// (0x6083..0x6085) in that unit per second, positions staying in increments; with factor_group
// positions are in feed-constant units (0x6092 feed per driving shaft revolution, 0x6091 motor
// revolutions per driving shaft revolution), velocities in them per s, accelerations per s^2,
// and the drive has no 0x60A8/0x60A9. A zero, or a value >= 2^31, in `factor_group` models a
// drive whose factor group a master must refuse. `absent_objects` lists optional objects the
// model lacks: SDO access and PDO mapping of them answer 06020000.
//
// Fixed PDO mapping (issue 20): `fixed_tpdo_mapping` (in drive, encoder, torque_sensor and
// input_encoder) models a device whose TPDO parameters are read-only, as some real devices have
// them: each key tpdo1..tpdo4 lists that TPDO's mapping as "INDEX:SUB/BITS" (BITS a multiple of
// 8; at most 8 objects and 64 bits), and its communication (0x180n) and mapping (0x1A0n)
// parameters answer an SDO write with abort 06010002. The PDO keeps the pre-defined COB-ID
// (0x180 + node id for TPDO1, 0x280 + node id for TPDO2, ...) and transmission type 1 (every
// SYNC); an empty list leaves it disabled (COB-ID bit 31 set). A TPDO not listed stays
// remappable, and so do the RPDOs: the bench maps the drive's RPDO1 with the controlword for its
// quick stop. An object the device does not have is refused when the bench is built.
// Every device section also takes `heartbeat_producer: false` (default true): a device with no
// heartbeat producer, no 0x1017 in its object dictionary, that a master must supervise by node
// guarding (it has 0x100C guard time and 0x100D life time factor, read-write, and answers remote
// frames on 0x700 + node id with its NMT state and the toggle bit).
//
// The gear's "true" parameters are not here: the CLI takes them from a twin-case file.

#include <filesystem>
#include <string>

#include "wavebench/simdevices/simulated_bench.hpp"

namespace wavebench::strict_yaml {
class YamlSection;
}

namespace wavebench::simdevices {

// Throws std::invalid_argument naming the key, the value and what was expected; unknown keys
// inside `simbench:` and what drivers/strict_yaml refuses (empty, not UTF-8, duplicate keys)
// are errors too.
SimulatedBenchConfig parse_simulated_bench_config(const std::string& yaml_text,
                                                  SimulatedBenchConfig base = {});
// The same with `source` (a file name) in the messages of the text checks.
SimulatedBenchConfig parse_simulated_bench_config(const std::string& yaml_text,
                                                  const std::string& source,
                                                  SimulatedBenchConfig base);
SimulatedBenchConfig load_simulated_bench_config(const std::filesystem::path& path,
                                                 SimulatedBenchConfig base = {});
// The `simbench:` section itself, for a config that holds one (a bench config's
// `simulated.simbench`); throws strict_yaml::RefusedConfig with the section's key paths.
SimulatedBenchConfig read_simulated_bench_section(strict_yaml::YamlSection& simbench,
                                                  SimulatedBenchConfig base = {});

// "i16", "i32", "f32" (also "int16", "int32", "real32").
DataType parse_process_value_type(const std::string& text);

}  // namespace wavebench::simdevices
