#pragma once
// What a procedure needs to know about the bench it runs on.

#include <string>
#include <vector>

#include "wavebench/model/gear_params.hpp"
#include "wavebench/model/gear_sense.hpp"

namespace wavebench::bench {

// bench.md §7. 0 (the default: the key absent from the bench config) switches that limit off;
// the config refuses a written value <= 0, so a sign typo cannot disarm a limit.
struct SafetyLimits {
  double max_input_speed_rad_s = 0;
  double max_brake_current_a = 0;
  double max_brake_torque_nm = 0;
  double max_measured_torque_nm = 0;
  double max_following_error_rad = 0;  // input side
  double max_coil_temperature_c = 0;
  double max_te_excursion_rad = 0;  // |TE| at the output
  double heartbeat_timeout_s = 0;   // consumer time per node
  double modbus_link_timeout_s = 0;
};

// A measuring device of the bench and its calibration as the bench config states it (the
// optional `calibration: {id, due}` of drive, encoder and torque_sensor): printed on a
// certificate. Empty id/due: the config does not say.
struct SensorCalibration {
  std::string sensor;  // "output encoder"
  std::string id;      // the calibration certificate's number
  std::string due;     // next calibration, YYYY-MM-DD
};

struct BenchDescription {
  std::string name;         // "sim" for the in-process simulated bench, or the config's name
  std::string unit_serial;  // the gear under test
  model::GearSense sense;   // ratio N and the output direction sign
  double sync_period_s = 1e-3;
  bool simulated_clock = false;
  double rated_torque_nm = 0;  // of the unit under test (lost-motion ladder, ±x % of rated)
  double max_brake_torque_nm = 0;
  // Noise of the sensors as configured (encoder, torque): the twin's residual floor.
  double output_encoder_noise_rad = 0;
  double input_encoder_resolution_rad = 0;
  // One step of the output encoder (2π / counts_per_turn as configured); 0 when the config
  // leaves counts_per_turn to be read from the device. Uncertainty budgets (q/√12).
  double output_encoder_resolution_rad = 0;
  double torque_noise_nm = 0;
  // The torque sensor's quantisation step (its scale per raw unit; 0: not known from the
  // config), for uncertainty budgets.
  double torque_resolution_nm = 0;
  // The twin's nominal gear (its own parameters, not the simulated unit's "true" ones).
  model::GearParams twin_gear;
  std::string twin_case_path;  // where twin_gear came from (copied into run folders)
  SafetyLimits limits;
  std::vector<SensorCalibration> sensors;  // input encoder (drive), output encoder, torque sensor
};

}  // namespace wavebench::bench
