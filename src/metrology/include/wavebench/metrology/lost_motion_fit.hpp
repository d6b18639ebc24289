#pragma once
// Lost motion, hysteresis and stiffness (bench.md §4) from a torque–twist record: the output
// moved slowly forward and back at a ladder of brake torques. Because a brake only resists,
// torque follows the direction of travel: the forward branch carries the torques of forward
// travel, the reverse branch those of reverse travel.
//
// The twist is modelled per branch as θ = o_branch + sign(T)·φ(|T|), φ the catalogue
// three-segment compliance (slopes 1/K1 up to T1, 1/K2 up to T2, 1/K3 above). The offsets and
// compliances are linear least squares for given breakpoints; the breakpoints are searched
// (grid, then refined). Backlash is the zero-torque intercept between the branches, o_f − o_r.

#include <nlohmann/json.hpp>
#include <span>
#include <vector>

namespace wavebench::metrology {

struct TorqueTwistPoint {
  double torque_nm = 0;
  double twist_rad = 0;  // TE at the output (GearSense::transmission_error)
  int travel = 1;        // +1 forward travel, −1 reverse travel
};

struct ThreeSegmentStiffness {
  double k1 = 0, k2 = 0, k3 = 0;  // N·m/rad
  double t1 = 0, t2 = 0;          // N·m
  double rms_residual_rad = 0;
  // Twist of the fitted curve at torque t (odd-symmetric, zero at zero torque).
  double twist_at(double torque_nm) const;
};

struct LostMotionOptions {
  double rated_torque_nm = 0;
  double lost_motion_fraction = 0.03;  // ±3 % of rated torque (catalogues use a few per cent)
  int breakpoint_grid = 60;            // candidates per breakpoint in the coarse search
  // Throws std::invalid_argument naming the key when out of range.
  void validate() const;
};

struct LostMotionResult {
  double lost_motion_rad = 0;        // θ_f(+x·T_rated) − θ_r(−x·T_rated)
  double lost_motion_torque_nm = 0;  // x·T_rated
  double backlash_rad = 0;           // o_f − o_r
  double forward_offset_rad = 0;     // o_f
  double reverse_offset_rad = 0;     // o_r
  double hysteresis_loss_j = 0;      // |∮ T dθ| over the record in acquisition order (N·m·rad)
  ThreeSegmentStiffness stiffness;
};

// The three-segment model above fitted to a record: per-branch offsets and compliances by
// linear least squares for given breakpoints, the breakpoints searched (a grid over
// 0 < t1 < t2 < max |T|, then three refinements around the best pair).
struct ThreeSegmentFit {
  ThreeSegmentStiffness stiffness;
  double forward_offset_rad = 0;  // o_f: the branch of travel > 0
  double reverse_offset_rad = 0;  // o_r
  double sse_rad2 = 0;
  int points = 0;
  // Standard uncertainties from the residual (GUM Type A): of the compliances 1/K1..1/K3,
  // s²·(AᵀA)⁻¹ at the breakpoints found with s² = SSE/(n − 5); of each breakpoint, the half
  // width of the range where the sum of squares stays within SSE + s² with the other held
  // (the profile's Δχ² = 1 interval).
  double compliance_standard[3] = {0, 0, 0};  // rad/(N·m)
  double t1_standard_nm = 0, t2_standard_nm = 0;
};

// Throws std::invalid_argument when a branch has fewer than two points or the record fewer
// than 7, or no breakpoint pair fits below the largest torque.
ThreeSegmentFit fit_three_segment(std::span<const TorqueTwistPoint> record, int breakpoint_grid);

// Throws std::invalid_argument when a branch is missing or has fewer than two torques, or the
// record cannot support three segments (fewer than 7 points).
LostMotionResult analyse_lost_motion(std::span<const TorqueTwistPoint> record,
                                     const LostMotionOptions& options);

// Area of the closed polygon through the points in order (shoelace), absolute.
double loop_area(std::span<const TorqueTwistPoint> record);

nlohmann::json to_json(const LostMotionResult& result);

}  // namespace wavebench::metrology
