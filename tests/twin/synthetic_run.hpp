#pragma once
// A recorded run from a known gear: the simulated bench's plant driven by a velocity loop
// through speed segments at brake loads, sampled at 1 kHz like SYNC, with the sensors' noise
// (input encoder quantised, output encoder Gaussian, torque Gaussian). The truth (the
// plant's own TE) is kept beside the measurement, so the noise floor is known exactly.

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "wavebench/model/gear_params.hpp"
#include "wavebench/metrology/gear_sense.hpp"
#include "wavebench/simdevices/bench_plant.hpp"
#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::twin::testing {

inline constexpr double kArcmin = std::numbers::pi / (180.0 * 60.0);
inline constexpr double kArcsec = kArcmin / 60.0;

// The "true" unit: N = 50 (100/102 teeth) so a whole output revolution takes seconds, a
// three-segment stiffness, 1 arcmin backlash, arcminute TE harmonics and a mesh line above
// the Nyquist rate, output drag the torque sensor does not see.
inline model::GearParams true_gear() {
  model::GearParams p;
  p.name = "test unit (true)";
  p.geometry.z_flex = 100;
  p.geometry.z_circ = 102;
  p.geometry.wave_number = 2;
  p.geometry.ratio = 50;
  p.inertia_input = 1.2e-4;
  p.inertia_output = 0.04;
  p.viscous_input = 2e-5;
  p.viscous_output = 0.05;
  p.te_terms = {
      {"output flange eccentricity", model::TeFamily::kOutputOnceRev, 1.3 * kArcmin, 0, 1, 0.4},
      {"dF_i1", model::TeFamily::kTangentialOutput, 1.1 * kArcmin, 2, 2, 1.1},
      {"dS_fix", model::TeFamily::kHousing, 0.35 * kArcmin, 2, 0, -0.7},
      {"T1l_1", model::TeFamily::kWaveGenerator, 0.2 * kArcmin, 1, 0, 2.0},
      {"df_i1 (base pitch)", model::TeFamily::kToothMesh, 0.01 * kArcmin, 204, 0, 0.3},
  };
  p.stiffness.law = model::ThreeSegmentStiffness{6.7e4, 29, 1.1e5, 108, 1.2e5};
  p.backlash.total_rad = 1.0 * kArcmin;
  p.damping.damping_ratio = 0.06;
  p.friction = model::CoulombStribeckFriction{0.02, 0.03, 0.5, 1e-5, 1e-2};
  // Drag above the torques the TE harmonics and the mesh line put through the gear at the
  // test speeds, so the driving flank stays in contact (with less, contact chatters and the
  // impacts make the output's motion sensitive to everything, model.md §10).
  p.load.output_drag_coulomb = 1.0;
  p.load.drag_smoothing_speed = 1e-3;
  return p;
}

// What a twin config would say before calibration: amplitudes and phases off, a missing
// term, 25 % softer, twice the backlash.
inline model::GearParams nominal_gear() {
  model::GearParams p = true_gear();
  p.name = "test unit (nominal)";
  p.te_terms = {
      {"output flange eccentricity", model::TeFamily::kOutputOnceRev, 1.0 * kArcmin, 0, 1, 0.0},
      {"dF_i1", model::TeFamily::kTangentialOutput, 0.8 * kArcmin, 2, 2, 0.6},
      {"T1l_1", model::TeFamily::kWaveGenerator, 0.3 * kArcmin, 1, 0, 1.0},
      {"df_i1 (base pitch)", model::TeFamily::kToothMesh, 0.01 * kArcmin, 204, 0, 0.3},
  };
  p.stiffness.law = model::ThreeSegmentStiffness{5.0e4, 29, 8.25e4, 108, 9e4};
  p.backlash.total_rad = 2.0 * kArcmin;
  return p;
}

struct Segment {
  double input_rpm = 0;  // signed
  double brake_nm = 0;
  double seconds = 0;
  bool recorded = true;  // false: a run-in, simulated but not sampled
};

struct SyntheticRun {
  std::vector<storage::SyncSample> samples;
  std::vector<double> true_te_rad;
  double noise_floor_arcsec = 0;  // RMS of measured − true TE
};

struct SensorNoise {
  double output_encoder_arcsec = 0.5;
  int input_counts_per_rev = 131072;
  int output_counts_per_rev = 0;  // 0: no quantisation of the output encoder
  double torque_nm = 0.02;
  unsigned seed = 7;
  double plant_substep = 2e-5;
};

inline SyntheticRun synthesise_run(const model::GearParams& gear,
                                   const std::vector<Segment>& segments,
                                   const SensorNoise& noise = {}, double sync_period = 1e-3) {
  simdevices::SimulatedBenchPlant plant(gear, noise.plant_substep);
  const double n = plant.ratio();
  std::mt19937 rng(noise.seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  const double count = 2 * std::numbers::pi / noise.input_counts_per_rev;
  SyntheticRun run;
  double integral = 0, speed_ref = 0;
  std::uint64_t index = 0;
  double squares = 0;
  const int control_steps = 4;  // velocity loop at 4 kHz
  double brake = 0;
  for (const auto& seg : segments) {
    const double target = seg.input_rpm * 2 * std::numbers::pi / 60;
    const auto cycles = static_cast<std::uint64_t>(std::llround(seg.seconds / sync_period));
    for (std::uint64_t c = 0; c < cycles; ++c) {
      for (int k = 0; k < control_steps; ++k) {
        const double h = sync_period / control_steps;
        // Speed reference ramps at 2000 rad/s^2: no step into the gear.
        speed_ref += std::clamp(target - speed_ref, -2000 * h, 2000 * h);
        const double error = speed_ref - plant.state().omega_in;
        integral += error * h;
        plant.set_motor_torque(0.05 * error + 2.0 * integral);
        // A powder brake's torque follows its coil current with a lag (bench.md §3).
        brake += (seg.brake_nm - brake) * h / 0.02;
        plant.set_brake_torque(brake);
        plant.step(h);
      }
      if (!seg.recorded) continue;
      const auto& s = plant.state();
      storage::SyncSample x;
      x.index = index;
      x.sync_counter = static_cast<std::uint32_t>(index % 240 + 1);
      x.flags = storage::kAllChannelsValid;
      x.receive_time_ns = static_cast<std::int64_t>(std::llround(s.t * 1e9));
      x.theta_in_rad = std::round(s.theta_in / count) * count;
      x.theta_out_rad = s.theta_out + noise.output_encoder_arcsec * kArcsec * unit(rng);
      if (noise.output_counts_per_rev > 0) {
        const double out_count = 2 * std::numbers::pi / noise.output_counts_per_rev;
        x.theta_out_rad = std::round(x.theta_out_rad / out_count) * out_count;
      }
      x.input_speed_rad_s = s.omega_in;
      x.torque_nm = s.shaft_torque + noise.torque_nm * unit(rng);
      x.brake_torque_nm = plant.brake_torque_setting();
      run.samples.push_back(x);
      run.true_te_rad.push_back(s.theta_out - s.theta_in / n);
      const double meas = x.theta_out_rad - x.theta_in_rad / n;
      squares += std::pow((meas - run.true_te_rad.back()) / kArcsec, 2);
      ++index;
    }
  }
  run.noise_floor_arcsec = std::sqrt(squares / static_cast<double>(run.samples.size()));
  return run;
}

inline metrology::GearSense sense_of(const model::GearParams& g) {
  return {g.geometry.ratio, g.geometry.direction_sign};
}

}  // namespace wavebench::twin::testing
