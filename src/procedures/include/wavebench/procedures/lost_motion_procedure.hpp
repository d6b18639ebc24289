#pragma once
// Lost motion, hysteresis and stiffness (bench.md §4). A brake only resists motion, so the
// torque follows the direction of travel: at each torque of a ladder the output is moved
// slowly forward, then back over the same span, and the twist (θ1/N − θ2 = −TE) and the
// measured torque are averaged over one and the same window of output angle in both
// directions. The window is one mesh period long (2π/z_F of the output), so the TE
// harmonics of U per wave-generator revolution and of the mesh average out of the twist and
// the output-angle ones are the same in both directions.

#include <nlohmann/json.hpp>
#include <string_view>
#include <vector>

#include "wavebench/bench/bench.hpp"
#include "wavebench/metrology/lost_motion_fit.hpp"
#include "wavebench/metrology/lost_motion_uncertainty.hpp"
#include "wavebench/procedures/option_reader.hpp"
#include "wavebench/procedures/procedure_progress.hpp"
#include "wavebench/procedures/run_plan.hpp"

namespace wavebench::procedures {

struct LostMotionOptions {
  // Brake torques as fractions of the unit's rated torque (capped below the brake's limits).
  std::vector<double> torque_fractions{0.02, 0.05, 0.1, 0.15, 0.25, 0.35, 0.45, 0.55, 0.7, 0.85};
  std::vector<double> torques_nm;      // explicit ladder [N·m]; overrides the fractions
  double input_speed_rad_s = 4.0;      // slow: the output at 0.04 rad/s for N = 100
  double run_in_output_rad = 0.008;    // before the window in each direction (takes up twist)
  double window_periods = 1;           // mesh periods (2π/z_F of the output) in the window
  double lost_motion_fraction = 0.03;  // report lost motion at ±3 % of rated
  double brake_settle_s = 0.3;

  static LostMotionOptions from_json(const nlohmann::json& options);
  // The options as the console shows them: one entry per key from_json accepts, in order.
  static std::vector<OptionSpec> schema();
  nlohmann::json to_json() const;
};

struct LostMotionOutcome {
  std::vector<metrology::TorqueTwistPoint> record;  // forward up the ladder, then reverse
  metrology::LostMotionResult result;
  metrology::LostMotionUncertainty uncertainty;  // of the fit's figures
  std::vector<double> ladder_nm;
  double rated_torque_nm = 0;
  // results.json "lost_motion_fit": lost motion, backlash, hysteresis, K1/K2/K3, T1/T2 and the
  // torque–twist points.
  nlohmann::json to_json() const;
};

class LostMotionProcedure {
 public:
  // Where run()'s outcome goes in results.json.
  static constexpr std::string_view kResultsSection = "lost_motion_fit";
  explicit LostMotionProcedure(LostMotionOptions options);
  // What run() will command on `bench` and for how long, without touching it. Throws
  // std::invalid_argument where run() would refuse the options on this bench.
  RunPlan plan(const bench::BenchDescription& bench) const;
  // Throws bench::BenchAborted when the bench trips, std::invalid_argument when the ladder
  // cannot be built (no rated torque).
  LostMotionOutcome run(bench::Bench& bench, const ProcedureProgress& progress = {}) const;

 private:
  LostMotionOptions options_;
};

}  // namespace wavebench::procedures
