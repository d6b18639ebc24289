#pragma once
// The locked-output torsional test's loop (bench.md §4, the catalogues' torsional stiffness
// curve): torque against twist (θ1/N − θ2 = −TE) over a first loading curve 0 → +T_max and
// one loop +T_max → −T_max → 0. The branch on which the twist rises (the first loading and the
// reloading from −T_max) and the one on which it falls (the unloading from +T_max) are read:
//
// - hysteresis loss: the twist width at zero torque, where the unloading branch arrives at
//   zero from +T_max and the reloading branch arrives at zero from −T_max;
// - backlash: the flat step at zero torque, on each branch the twist between where it arrives
//   at zero torque and where it leaves it on the other side (mean of the two branches);
// - lost motion: the twist between the loop's mid-points at +x % and −x % of rated torque
//   (the mid-point of the two branches at each torque, as Harmonic Drive and Nabtesco
//   catalogues read it);
// - K1/K2/K3 and T1/T2: the catalogue three-segment curve fitted to the loop's mean curve (the
//   mean of the two branches at each measured torque).
//
// Values at a torque are read from a straight line through the branch's nearest points on that
// side of zero, outside the flat step. Every figure carries a GUM budget (k = 2).

#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "wavebench/metrology/lost_motion_fit.hpp"
#include "wavebench/metrology/uncertainty_budget.hpp"

namespace wavebench::metrology {

enum class LoopBranch {
  kFirstLoading,  // input forward from the locked start until +T_max (twist rising)
  kUnloading,     // input back from +T_max through zero to −T_max (twist falling)
  kReloading,     // input forward from −T_max to zero torque (twist rising)
};
const char* loop_branch_name(LoopBranch branch);  // "first_loading", "unloading", "reloading"

struct LoopPoint {
  LoopBranch branch = LoopBranch::kFirstLoading;
  double torque_nm = 0;  // the gear's torque in the model's sense
  double twist_rad = 0;  // θ1/N − θ2 at the output
  // Noise left after averaging the point's window (standard deviation of the mean).
  double twist_standard_rad = 0;
  double torque_standard_nm = 0;
  bool voided = false;  // the output slipped: kept in the record, left out of the analysis
};

// What the budget's Type B terms are built from.
struct LoopSensors {
  double ratio = 0;                    // N
  double output_encoder_step_rad = 0;  // quantisation step q of the output encoder (0: none)
  double input_encoder_step_rad = 0;   // of the input encoder, at the input shaft
  double torque_step_nm = 0;           // of the torque sensor (0: none)
  // Kinematic TE terms that change while the input turns with the output locked: amplitude
  // [rad at the output] and order per wave-generator revolution (the twin's nominal ones).
  struct InputTerm {
    double amplitude_rad = 0;
    double order_input = 0;
  };
  std::vector<InputTerm> input_terms;
};

struct TorsionalLoopOptions {
  double rated_torque_nm = 0;
  double lost_motion_fraction = 0.03;  // lost motion at ± this fraction of rated
  double zero_band_nm = 0.5;           // |T| at or under it: the flat step at zero torque
  int local_points = 4;                // points of each local line
  int breakpoint_grid = 60;
  // Throws std::invalid_argument naming the key when out of range.
  void validate() const;
};

struct TorsionalLoopResult {
  UncertainFigure hysteresis_loss_rad;
  UncertainFigure lost_motion_rad;
  UncertainFigure backlash_rad;
  UncertainFigure k1_nm_per_rad, k2_nm_per_rad, k3_nm_per_rad;
  UncertainFigure t1_nm, t2_nm;
  double lost_motion_torque_nm = 0;
  double fit_rms_residual_rad = 0;
  // Where each branch reaches zero torque from either side (the ends of the flat step).
  double unloading_zero_from_above_rad = 0, unloading_zero_from_below_rad = 0;
  double rising_zero_from_above_rad = 0, rising_zero_from_below_rad = 0;
  double peak_torque_nm = 0, valley_torque_nm = 0;  // largest and smallest used
  int points_used = 0;
  int points_voided = 0;
  int flat_step_points = 0;  // used points within the zero band
  // The mean curve the stiffness was fitted to: torque and mid-point twist.
  std::vector<double> mean_torque_nm, mean_twist_rad;
};

// Throws std::invalid_argument when a branch has too few points on a side of zero (fewer than
// two beyond the zero band), or the mean curve cannot carry three segments.
TorsionalLoopResult analyse_torsional_loop(std::span<const LoopPoint> points,
                                           const LoopSensors& sensors,
                                           const TorsionalLoopOptions& options);

// Figures as uncertain figures (angles in arcmin, stiffness in N·m/rad, torques in N·m).
nlohmann::json to_json(const TorsionalLoopResult& result);

}  // namespace wavebench::metrology
