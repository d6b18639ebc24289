#pragma once
// Speed sweep up and down (model.md §9, seed 001: 100 -> 2700 rpm): response amplitude and
// Poincare points against speed (bifurcation data), jumps and the hysteresis between sweeps.
//
// simulate() takes no initial state, so each direction is ONE run with a kinematic input trace
// that steps through the speeds (smooth speed ramps between the plateaus): every speed
// continues from the state the previous one left, which is what makes up and down differ.

#include <string>
#include <vector>

#include "wavebench/analysis/analysis_options.hpp"
#include "wavebench/model/simulation.hpp"

namespace wavebench::analysis {

struct SweepPoint {
  double speed = 0;                // input speed [rad/s]
  double rms = 0;                  // of the analysed signal (mean removed) over the record window
  double amplitude = 0;            // half peak-to-peak
  std::vector<double> poincare_x;  // section points (Delta) in the record window
};

struct SweepJump {
  std::string direction;  // "up" or "down"
  double from_speed = 0, to_speed = 0;
  double from_amplitude = 0, to_amplitude = 0;
  double relative_change = 0;
};

struct SpeedSweep {
  std::vector<SweepPoint> up;
  std::vector<SweepPoint> down;  // in descending speed
  std::vector<SweepJump> jumps;
  double max_hysteresis = 0;              // largest |up - down| / max(up, down) at one speed
  double hysteresis_speed = 0;            // where it occurs
  double hysteresis_area = 0;             // integral of |up - down| over speed [unit * rad/s]
  std::vector<double> hysteresis_speeds;  // speeds where the difference exceeds the threshold
};

// Speed plateaus of a sweep (ascending), the kinematic trace that realises them, and the windows.
std::vector<double> sweep_speeds(const SweepOptions& options);
model::KinematicInput sweep_trace(const std::vector<double>& speeds, double settle_time,
                                  double record_time, double ramp_time, double* total_time);

// Jumps between neighbours of one direction (points in the order swept).
std::vector<SweepJump> find_jumps(const std::vector<SweepPoint>& points,
                                  const std::string& direction, double threshold);
// Fills the hysteresis fields of `sweep` from up and down.
void measure_hysteresis(SpeedSweep& sweep, double threshold);

SpeedSweep run_speed_sweep(const model::GearParams& params, const model::SimulationOptions& sim,
                           const SweepOptions& options, const std::string& signal,
                           const model::TeTerm* strobe_term);

}  // namespace wavebench::analysis
