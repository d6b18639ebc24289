#pragma once
// The gear model driven by what the bench measures (bench.md §5): the input angle θ_in as a
// kinematic input (model.md §2, a measured trace, monotone PCHIP through the samples) and the
// measured load torque on the output; it predicts θ_out and so the TE at every sample.
//
// Why integrate the dynamics rather than a quasi-static twist: the gear's output mode
// (sqrt(K/J2), 120-210 Hz for the bench units) lies below the 1 kHz SYNC rate and the tooth
// mesh line (2·z_C·f_H, ~900 Hz at 100 rpm) above the output mode, so the output flange does
// not follow the mesh error: a quasi-static twin would put the whole mesh error into the
// predicted TE (aliased), the measurement shows a few per cent of it. So the model's own
// Dormand–Prince integrator runs from sample to sample (restarted at each sample time, with
// the backlash contact events located), and the twin reads its state at each sample.
//
// Causality: the PCHIP slope at a sample needs the next sample, so the twin integrates up to
// the last-but-one sample it has (one sample of lag by design, plus the smoother's k samples,
// see TwinSolverOptions); flush() finishes the rest.
// Friction at the wave generator and the brake model are dropped from the twin's parameters:
// with a prescribed input angle friction only changes the motor torque, and the measured shaft
// torque replaces the brake (drag and viscous losses of the output side stay, the torque
// sensor does not see them).

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "wavebench/model/gear_params.hpp"
#include "wavebench/metrology/gear_sense.hpp"
#include "wavebench/storage/sync_sample.hpp"
#include "wavebench/twin/twin_point.hpp"

namespace wavebench::twin {

struct TwinSolverOptions {
  double rtol = 1e-6;
  double atol = 1e-9;   // times the model's characteristic sizes
  double max_step = 0;  // [s] 0 = no limit
  // Start the output where the first sample measured it when that lies within the clearance
  // (plus ~20 arcsec) of the model's steady state, else at the steady state.
  bool start_from_measured_output = true;
  // The drive (θ_in and torque) goes through a centred Savitzky–Golay smoother (quadratic,
  // 2·k + 1 samples; 0 = off) before it moves the model: the sensors' noise is not motion, and
  // a quantised input angle or a noisy torque rings the output mode. Quadratic trends (ramps)
  // pass unchanged; a window whose sample times are not evenly spaced (a late SYNC, a gap)
  // passes raw. Costs k samples of lag (the longer window's). TE is still predicted against
  // the measured θ_in. A longer angle window blurs the servo's turn at a reversal.
  int smoothing_half_width = 3;
  // The torque's window (the look-ahead is the longer of the two). Where it disagrees with a
  // 5-sample window by more than 4 σ of the torque noise (estimated from the stream's third
  // differences), the short window is used: a holding brake's torque turns over within a few
  // samples at a reversal, where the input angle stays smooth.
  int torque_smoothing_half_width = 6;
  // How much older the input angle is than the output angle in a sample [s] (a drive that
  // reports the position of its last control cycle rather than at SYNC): the predicted TE
  // carries it as ω1·delay/N, so that it compares with the measured one. The calibration fits
  // it when the run's speed varies.
  double input_latch_delay_s = 0;
};

// The twin's parameters for a measured drive: kinematic input, no friction, no brake model,
// no prescribed load (the measured torque is the load).
model::GearParams measured_drive_params(const model::GearParams& nominal);

TwinSampleInput twin_input(const storage::SyncSample& sample);

class MeasuredDriveTwin {
 public:
  // Throws std::invalid_argument when the gear cannot be simulated or its ratio is not the
  // bench's (sense.ratio).
  MeasuredDriveTwin(const model::GearParams& gear, const metrology::GearSense& sense,
                    TwinSolverOptions options = {});
  ~MeasuredDriveTwin();
  MeasuredDriveTwin(const MeasuredDriveTwin&) = delete;
  MeasuredDriveTwin& operator=(const MeasuredDriveTwin&) = delete;

  // Takes the next sample (times ascending; a time not after the previous one is nudged
  // forward by 0.1 µs) and integrates as far as it can.
  void push(const TwinSampleInput& sample);
  // Integrates to the last sample.
  void flush();

  // One point per pushed sample, in order; predictions fill in as the twin advances. The
  // points that change no more are appended to `out` and let go (a live twin of hours keeps
  // only those in flight); returns how many.
  std::size_t take_settled_points(std::vector<TwinPoint>& out);
  // Every point not taken yet, settled or not (after flush(): all settled).
  std::vector<TwinPoint> take_points();
  bool started() const;
  // Bench time [s] the twin has reached (NaN before the first prediction).
  double twin_time_s() const;
  std::uint64_t predicted() const;
  std::int64_t solver_steps() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The twin over a recorded run, start to end.
std::vector<TwinPoint> replay_twin(const model::GearParams& gear,
                                   const metrology::GearSense& sense,
                                   std::span<const storage::SyncSample> samples,
                                   TwinSolverOptions options = {});

}  // namespace wavebench::twin
