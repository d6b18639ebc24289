#pragma once
// Static TE (bench.md §4): per direction and load, the TE at each settled position, its mean,
// peak-to-peak and standard deviation; the lost motion at each position (|reverse − forward|);
// the shift of mean TE under load and the stiffness it implies (K ≈ T / shift).
//
// Standard deviation is the population one (divide by n): the positions sample one whole
// output revolution evenly, so this is the RMS of TE about its mean over the revolution, the
// same quantity the dynamic procedure reports as RMS.

#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "wavebench/metrology/gear_sense.hpp"
#include "wavebench/metrology/uncertainty_budget.hpp"

namespace wavebench::metrology {

enum class Direction { kForward, kReverse };
const char* direction_name(Direction direction);

struct StaticTePoint {  // averages over the window at one settled position
  int position = 0;     // index 0..n-1 over the output revolution
  double theta_in_rad = 0;
  double theta_out_rad = 0;
  double torque_nm = 0;
  // Standard uncertainty of the window's mean TE from the scatter of its samples (correlation
  // allowed for: standard_of_window_mean); 0 when not known.
  double te_noise_rad = 0;
};

struct StaticTePass {
  Direction direction = Direction::kForward;
  double load_nm = 0;  // brake torque commanded
  std::vector<StaticTePoint> points;
};

struct StaticTePointResult {
  int position = 0;
  double output_angle_deg = 0;  // θ2 in degrees, in [0, 360)
  double te_arcmin = 0;
  double torque_nm = 0;
  UncertainFigure te;  // te_arcmin with its budget (arcmin)
};

// What the static figures' uncertainty is built from besides each window's own scatter
// (bench.md §4): the encoders' steps and the settle detector's drift allowance.
struct StaticTeUncertaintyInputs {
  double input_resolution_rad = 0;   // one step of θ_in (the drive's encoder); 0: unknown
  double output_resolution_rad = 0;  // one step of θ_out; 0: unknown
  // max − min of the output angle the settle detector accepts over its window: where in that
  // band the output came to rest is unknown, a rectangular distribution of this full width.
  double settle_drift_rad = 0;
};

// The budget of one position's TE [arcmin]: output encoder quantisation q_out/√12, input
// encoder quantisation (q_in/N)/√12 (θ_in enters TE divided by N), the noise left after window
// averaging, and the settle criterion (drift/2)/√3. Terms whose input is 0 are left out.
UncertainFigure static_point_uncertainty(double te_arcmin, double te_noise_rad,
                                         const StaticTeUncertaintyInputs& inputs,
                                         const GearSense& sense);

// One settled position's figures as results.json gives them (angle within a revolution, TE and
// its budget).
StaticTePointResult static_point_result(const StaticTePoint& point, const GearSense& sense,
                                        const StaticTeUncertaintyInputs& inputs);

struct StaticTeSummary {
  Direction direction = Direction::kForward;
  double load_nm = 0;
  double mean_arcmin = 0;
  double p2p_arcmin = 0;
  double std_arcmin = 0;  // population
  double mean_torque_nm = 0;
  std::vector<StaticTePointResult> points;
  UncertainFigure mean, p2p, std;  // the figures above with their budgets (arcmin)
};

struct LostMotionProfile {  // |reverse − forward| at each position, one load
  double load_nm = 0;
  std::vector<int> positions;
  std::vector<double> lost_motion_arcmin;
  double mean_arcmin = 0;
  double max_arcmin = 0;
  double max_abs_arcmin = 0;  // the largest |forward − reverse|: the width a limit judges
  std::vector<UncertainFigure> per_position;  // each lost_motion_arcmin with its budget
  UncertainFigure mean, max, max_abs;
};

struct LoadShift {  // mean TE at a load minus mean TE at the lowest load, same direction
  Direction direction = Direction::kForward;
  double load_nm = 0;
  double reference_load_nm = 0;
  double shift_arcmin = 0;
  std::optional<double> stiffness_nm_per_rad;  // (load − reference) / shift; none if shift = 0
  UncertainFigure shift;                       // arcmin
  std::optional<UncertainFigure> stiffness;    // N·m/rad, from the shift's relative uncertainty
};

struct StaticTeResult {
  std::vector<StaticTeSummary> passes;  // in input order
  std::vector<LostMotionProfile> lost_motion;
  std::vector<LoadShift> load_shifts;
};

StaticTeSummary summarise_static_pass(const StaticTePass& pass, const GearSense& sense,
                                      const StaticTeUncertaintyInputs& uncertainty = {});
// Throws std::invalid_argument for an empty pass or a bad GearSense.
StaticTeResult analyse_static_te(std::span<const StaticTePass> passes, const GearSense& sense,
                                 const StaticTeUncertaintyInputs& uncertainty = {});

// results.json: {"static": [{direction, load_nm, mean_arcmin, p2p_arcmin, std_arcmin,
// uncertainty: {mean_arcmin, p2p_arcmin, std_arcmin},
// points: [{position, output_angle_deg, te_arcmin, torque_nm, uncertainty: {te_arcmin}}]}],
// "lost_motion": [...], "load_shift": [...]}; every `uncertainty` entry is an UncertainFigure
// (to_json) of the figure of the same name beside it.
nlohmann::json to_json(const StaticTeResult& result);

}  // namespace wavebench::metrology
