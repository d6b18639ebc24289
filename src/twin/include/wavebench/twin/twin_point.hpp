#pragma once
// What the twin takes from each SYNC sample and what it gives back for it.

#include <cstdint>

namespace wavebench::twin {

// The part of a storage::SyncSample the twin needs (copied on the bench thread).
struct TwinSampleInput {
  std::uint64_t index = 0;
  std::int64_t time_ns = 0;  // the sample's receive time, bench time
  std::uint32_t flags = 0;   // storage::SampleFlag bits
  double theta_in_rad = 0;
  double theta_out_rad = 0;
  double torque_nm = 0;
};

// One sample as the twin saw it. NaN marks what is not available: measured TE when θ_in or
// θ_out was missing, the prediction when θ_in was missing (the twin is driven by it) or the
// twin did not get that far.
struct TwinPoint {
  std::uint64_t index = 0;
  double t_s = 0;
  double theta1_rad = 0;  // input angle (model θ1 = measured θ_in)
  double theta2_rad = 0;  // measured output angle in the model's convention (s·θ_out)
  double measured_te_rad = 0;
  double predicted_te_rad = 0;
  // From the twin's state at this sample, for calibration: the TE excitation e(θ1, θ2), the
  // backlash-filtered spring twist x, the output speed and the gear torque.
  double excitation_rad = 0;
  double spring_twist_rad = 0;
  double twist_rad = 0;
  double omega1_rad_s = 0;  // input speed the twin was driven with
  double omega2_rad_s = 0;
  double gear_torque_nm = 0;
};

}  // namespace wavebench::twin
