#pragma once
// Torsional stiffness with the output locked (bench.md §4, the catalogues' definition): the
// powder brake holds up to its set torque in both directions while the output stands still,
// so it is set above the loop's peak; the input then turns in small position steps until the
// measured torque reaches +T_max, back through zero to −T_max, and forward to zero again. At
// each step the twist (θ1/N − θ2) and the torque are averaged over a window once the step has
// settled. The output encoder catches slip: a point whose output moved beyond a threshold from
// where it was locked is voided and reported; more slipped points than allowed abort the run.
// The loop's figures come from metrology::analyse_torsional_loop.

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "wavebench/bench/bench.hpp"
#include "wavebench/metrology/torsional_loop.hpp"
#include "wavebench/procedures/option_reader.hpp"
#include "wavebench/procedures/procedure_progress.hpp"
#include "wavebench/procedures/run_plan.hpp"

namespace wavebench::procedures {

struct TorsionalOptions {
  double t_max_nm = 0;           // peak torque of the loop; 0: the unit's rated torque
  double hold_torque_nm = 0;     // brake setting; 0: 95 % of the brake's and the safety limit
  double hold_margin = 0.1;      // T_max stays below hold / (1 + margin)
  double twist_step_rad = 2e-5;  // output twist per input step (the input moves N times it)
  double input_speed_rad_s = 0.2;
  double settle_s = 0.05;       // after each step, before the window
  double window_s = 0.1;        // twist and torque averaged over it
  double brake_settle_s = 0.5;  // after setting the hold torque
  double lost_motion_fraction = 0.03;
  double zero_band_fraction = 0.005;   // |T| under this fraction of rated: the flat step
  double slip_threshold_rad = 2.9e-4;  // 1 arcmin of output motion voids a point
  int max_slipped_points = 3;          // more abort the run
  double max_twist_rad = 0.006;        // abort when T_max is not reached within this twist

  static TorsionalOptions from_json(const nlohmann::json& options);
  // The options as the console shows them: one entry per key from_json accepts, in order.
  static std::vector<OptionSpec> schema();
  nlohmann::json to_json() const;
};

// The torque levels of the test on a bench, and why T_max is what it is.
struct TorsionalTorques {
  double hold_nm = 0;
  double t_max_nm = 0;
  std::string t_max_reason;
};

struct TorsionalPoint {
  metrology::LoopPoint loop;
  double output_moved_rad = 0;  // from where the output was locked (after the last slip)
  double theta_in_rad = 0;      // the window's mean input angle
  double theta2_rad = 0;        // and output angle, in the model's sense (θ2)
};

struct TorsionalOutcome {
  std::vector<TorsionalPoint> points;  // in acquisition order
  metrology::TorsionalLoopResult result;
  TorsionalTorques torques;
  double rated_torque_nm = 0;
  double slip_threshold_rad = 0;
  double max_output_moved_rad = 0;
  int slipped_points = 0;
  // results.json "torsional".
  nlohmann::json to_json() const;
};

class TorsionalProcedure {
 public:
  // Where run()'s outcome goes in results.json.
  static constexpr std::string_view kResultsSection = "torsional";
  explicit TorsionalProcedure(TorsionalOptions options);
  // What run() will command on `bench` and for how long, without touching it. Throws
  // std::invalid_argument where run() would refuse the options on this bench.
  RunPlan plan(const bench::BenchDescription& bench) const;
  // Throws bench::BenchAborted when the bench trips, std::runtime_error when the output slips
  // more than allowed or T_max is not reached within max_twist_rad.
  TorsionalOutcome run(bench::Bench& bench, const ProcedureProgress& progress = {}) const;

  // The hold torque and T_max on `bench`; throws std::invalid_argument when they do not fit.
  TorsionalTorques torques(const bench::BenchDescription& bench) const;

 private:
  TorsionalOptions options_;
};

}  // namespace wavebench::procedures
