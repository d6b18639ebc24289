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
//               following_error_timeout_ms: 50, serial_number: 4097}
//     encoder: {node_id: 3, resolution: 1048576, revolutions: 2048, noise_arcsec: 0.5, seed: 3}
//     torque_sensor: {node_id: 4, object: "0x6130:1", type: i32, scale: 0.001,
//                     noise_nm: 0.02, offset_nm: 0, seed: 4}
//     input_encoder: {node_id: 5, resolution: 1048576, revolutions: 1, noise_arcsec: 0.5,
//                     seed: 5}   # absent: no input-side encoder (seed 004's bench has one)
//
// The gear's "true" parameters are not here: the CLI takes them from a twin-case file.

#include <filesystem>
#include <string>

#include "wavebench/simdevices/simulated_bench.hpp"

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

// "i16", "i32", "f32" (also "int16", "int32", "real32").
DataType parse_process_value_type(const std::string& text);

}  // namespace wavebench::simdevices
