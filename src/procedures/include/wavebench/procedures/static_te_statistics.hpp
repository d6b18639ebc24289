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

#include "wavebench/procedures/gear_sense.hpp"

namespace wavebench::procedures {

enum class Direction { kForward, kReverse };
const char* direction_name(Direction direction);

struct StaticTePoint {  // averages over the window at one settled position
  int position = 0;     // index 0..n-1 over the output revolution
  double theta_in_rad = 0;
  double theta_out_rad = 0;
  double torque_nm = 0;
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
};

struct StaticTeSummary {
  Direction direction = Direction::kForward;
  double load_nm = 0;
  double mean_arcmin = 0;
  double p2p_arcmin = 0;
  double std_arcmin = 0;  // population
  double mean_torque_nm = 0;
  std::vector<StaticTePointResult> points;
};

struct LostMotionProfile {  // |reverse − forward| at each position, one load
  double load_nm = 0;
  std::vector<int> positions;
  std::vector<double> lost_motion_arcmin;
  double mean_arcmin = 0;
  double max_arcmin = 0;
};

struct LoadShift {  // mean TE at a load minus mean TE at the lowest load, same direction
  Direction direction = Direction::kForward;
  double load_nm = 0;
  double reference_load_nm = 0;
  double shift_arcmin = 0;
  std::optional<double> stiffness_nm_per_rad;  // (load − reference) / shift; none if shift = 0
};

struct StaticTeResult {
  std::vector<StaticTeSummary> passes;  // in input order
  std::vector<LostMotionProfile> lost_motion;
  std::vector<LoadShift> load_shifts;
};

StaticTeSummary summarise_static_pass(const StaticTePass& pass, const GearSense& sense);
// Throws std::invalid_argument for an empty pass or a bad GearSense.
StaticTeResult analyse_static_te(std::span<const StaticTePass> passes, const GearSense& sense);

// results.json: {"static": [{direction, load_nm, mean_arcmin, p2p_arcmin, std_arcmin,
// points: [{position, output_angle_deg, te_arcmin, torque_nm}]}], "lost_motion": [...],
// "load_shift": [...]}
nlohmann::json to_json(const StaticTeResult& result);

}  // namespace wavebench::procedures
