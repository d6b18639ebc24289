#include "wavebench/metrology/lost_motion_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "wavebench/metrology/gear_sense.hpp"

namespace wavebench::metrology {

namespace {

// Compliance basis at |T| for breakpoints t1 < t2: the length of |T| in each segment.
Eigen::Vector3d segment_lengths(double t, double t1, double t2) {
  return {std::min(t, t1), std::clamp(t - t1, 0.0, t2 - t1), std::max(t - t2, 0.0)};
}

struct LinearFit {
  Eigen::VectorXd x;  // o_f, o_r, c1, c2, c3
  double sse = std::numeric_limits<double>::infinity();
};

// Columns o_f, o_r, c1, c2, c3 of the model twist = o_branch + sign(T)·Σ c_i·segment_i(|T|).
Eigen::MatrixXd design_matrix(std::span<const TorqueTwistPoint> record, double t1, double t2) {
  const auto n = static_cast<Eigen::Index>(record.size());
  Eigen::MatrixXd a(n, 5);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& p = record[static_cast<std::size_t>(i)];
    const double sign = p.torque_nm >= 0 ? 1.0 : -1.0;
    const Eigen::Vector3d s = segment_lengths(std::abs(p.torque_nm), t1, t2) * sign;
    a.row(i) << (p.travel > 0 ? 1.0 : 0.0), (p.travel > 0 ? 0.0 : 1.0), s(0), s(1), s(2);
  }
  return a;
}

LinearFit fit_for_breakpoints(std::span<const TorqueTwistPoint> record, double t1, double t2) {
  const auto n = static_cast<Eigen::Index>(record.size());
  const Eigen::MatrixXd a = design_matrix(record, t1, t2);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) b(i) = record[static_cast<std::size_t>(i)].twist_rad;
  LinearFit f;
  f.x = a.colPivHouseholderQr().solve(b);
  f.sse = (a * f.x - b).squaredNorm();
  return f;
}

// Twist of one branch at a torque, interpolated linearly between its points sorted by torque
// (extrapolated from the two nearest at the ends).
double branch_twist_at(std::span<const TorqueTwistPoint> record, int travel, double torque) {
  std::vector<std::pair<double, double>> pts;
  for (const auto& p : record) {
    if ((p.travel > 0) == (travel > 0)) pts.emplace_back(p.torque_nm, p.twist_rad);
  }
  std::sort(pts.begin(), pts.end());
  std::size_t j = 0;
  while (j + 2 < pts.size() && pts[j + 1].first < torque) ++j;
  const auto& [t0, y0] = pts[j];
  const auto& [t1, y1] = pts[j + 1];
  if (t1 == t0) return 0.5 * (y0 + y1);
  return y0 + (torque - t0) / (t1 - t0) * (y1 - y0);
}

}  // namespace

double ThreeSegmentStiffness::twist_at(double torque_nm) const {
  const Eigen::Vector3d s = segment_lengths(std::abs(torque_nm), t1, t2);
  const double phi = s(0) / k1 + s(1) / k2 + s(2) / k3;
  return torque_nm >= 0 ? phi : -phi;
}

void LostMotionOptions::validate() const {
  if (!(rated_torque_nm > 0)) {
    throw std::invalid_argument("lost_motion.rated_torque_nm = " + std::to_string(rated_torque_nm) +
                                "; expected > 0");
  }
  if (!(lost_motion_fraction > 0 && lost_motion_fraction < 1)) {
    throw std::invalid_argument("lost_motion.fraction = " + std::to_string(lost_motion_fraction) +
                                "; expected between 0 and 1 (e.g. 0.03 for ±3 %)");
  }
  if (breakpoint_grid < 4) {
    throw std::invalid_argument("lost_motion.breakpoint_grid = " + std::to_string(breakpoint_grid) +
                                "; expected >= 4");
  }
}

double loop_area(std::span<const TorqueTwistPoint> record) {
  double twice = 0;
  for (std::size_t i = 0; i < record.size(); ++i) {
    const auto& p = record[i];
    const auto& q = record[(i + 1) % record.size()];
    twice += p.twist_rad * q.torque_nm - q.twist_rad * p.torque_nm;
  }
  return std::abs(twice) / 2;
}

ThreeSegmentFit fit_three_segment(std::span<const TorqueTwistPoint> record, int breakpoint_grid) {
  std::size_t forward = 0, reverse = 0;
  double t_max = 0;
  for (const auto& p : record) {
    (p.travel > 0 ? forward : reverse) += 1;
    t_max = std::max(t_max, std::abs(p.torque_nm));
  }
  if (forward < 2 || reverse < 2 || record.size() < 7) {
    throw std::invalid_argument("torque–twist record: " + std::to_string(forward) +
                                " forward and " + std::to_string(reverse) +
                                " reverse points; expected at least 2 in each branch and 7 in all");
  }
  // Coarse grid over t1 < t2 in (0, t_max), then three refinements around the best pair.
  double best_t1 = 0, best_t2 = 0;
  LinearFit best;
  const int g = std::max(4, breakpoint_grid);
  double lo1 = 0, hi1 = t_max, lo2 = 0, hi2 = t_max;
  for (int round = 0; round < 4; ++round) {
    for (int i = 1; i < g; ++i) {
      const double t1 = lo1 + (hi1 - lo1) * i / g;
      for (int j = 1; j < g; ++j) {
        const double t2 = lo2 + (hi2 - lo2) * j / g;
        if (!(t2 > t1 && t1 > 0 && t2 < t_max)) continue;
        auto f = fit_for_breakpoints(record, t1, t2);
        if (f.sse < best.sse) {
          best = std::move(f);
          best_t1 = t1;
          best_t2 = t2;
        }
      }
    }
    const double w1 = 2 * (hi1 - lo1) / g, w2 = 2 * (hi2 - lo2) / g;
    lo1 = std::max(0.0, best_t1 - w1);
    hi1 = std::min(t_max, best_t1 + w1);
    lo2 = std::max(0.0, best_t2 - w2);
    hi2 = std::min(t_max, best_t2 + w2);
  }
  if (!std::isfinite(best.sse)) {
    throw std::invalid_argument(
        "torque–twist record: no breakpoint pair fits below the largest torque " +
        std::to_string(t_max) + " N·m");
  }
  ThreeSegmentFit out;
  out.forward_offset_rad = best.x(0);
  out.reverse_offset_rad = best.x(1);
  out.stiffness.t1 = best_t1;
  out.stiffness.t2 = best_t2;
  out.stiffness.k1 = 1.0 / best.x(2);
  out.stiffness.k2 = 1.0 / best.x(3);
  out.stiffness.k3 = 1.0 / best.x(4);
  out.sse_rad2 = best.sse;
  out.points = static_cast<int>(record.size());
  out.stiffness.rms_residual_rad = std::sqrt(best.sse / static_cast<double>(record.size()));

  // Type A uncertainties from the residual.
  const double dof = static_cast<double>(record.size()) - 5;
  const double s2 = dof > 0 ? best.sse / dof : 0;
  const auto a = design_matrix(record, best_t1, best_t2);
  const Eigen::MatrixXd ata = a.transpose() * a;
  const Eigen::MatrixXd cov = s2 * ata.completeOrthogonalDecomposition().pseudoInverse();
  for (int i = 0; i < 3; ++i)
    out.compliance_standard[i] = std::sqrt(std::max(0.0, cov(2 + i, 2 + i)));
  // Profile of each breakpoint with the other held: where SSE <= SSE_min + s².
  const auto profile_half_width = [&](bool first) {
    const double centre = first ? best_t1 : best_t2;
    const double lo = first ? 0.0 : best_t1, hi = first ? best_t2 : t_max;
    const double span = 0.25 * t_max;
    double inside_lo = centre, inside_hi = centre;
    constexpr int kSteps = 400;
    for (int k = -kSteps; k <= kSteps; ++k) {
      const double t = centre + span * k / kSteps;
      if (!(t > lo && t < hi)) continue;
      const double sse = first ? fit_for_breakpoints(record, t, best_t2).sse
                               : fit_for_breakpoints(record, best_t1, t).sse;
      if (sse <= best.sse + s2) {
        inside_lo = std::min(inside_lo, t);
        inside_hi = std::max(inside_hi, t);
      }
    }
    // Never narrower than the scan's own step.
    return std::max(0.5 * (inside_hi - inside_lo), 0.5 * span / kSteps);
  };
  out.t1_standard_nm = profile_half_width(true);
  out.t2_standard_nm = profile_half_width(false);
  return out;
}

LostMotionResult analyse_lost_motion(std::span<const TorqueTwistPoint> record,
                                     const LostMotionOptions& options) {
  options.validate();
  const auto fit = fit_three_segment(record, options.breakpoint_grid);
  LostMotionResult r;
  r.forward_offset_rad = fit.forward_offset_rad;
  r.reverse_offset_rad = fit.reverse_offset_rad;
  r.backlash_rad = r.forward_offset_rad - r.reverse_offset_rad;
  r.stiffness = fit.stiffness;

  r.lost_motion_torque_nm = options.lost_motion_fraction * options.rated_torque_nm;
  r.lost_motion_rad = branch_twist_at(record, +1, r.lost_motion_torque_nm) -
                      branch_twist_at(record, -1, -r.lost_motion_torque_nm);
  r.hysteresis_loss_j = loop_area(record);
  return r;
}

nlohmann::json to_json(const LostMotionResult& r) {
  return {{"lost_motion_arcmin", r.lost_motion_rad * kArcminPerRad},
          {"lost_motion_torque_nm", r.lost_motion_torque_nm},
          {"backlash_arcmin", r.backlash_rad * kArcminPerRad},
          {"hysteresis_loss_j", r.hysteresis_loss_j},
          {"stiffness",
           {{"k1_nm_per_rad", r.stiffness.k1},
            {"k2_nm_per_rad", r.stiffness.k2},
            {"k3_nm_per_rad", r.stiffness.k3},
            {"t1_nm", r.stiffness.t1},
            {"t2_nm", r.stiffness.t2},
            {"rms_residual_arcsec", r.stiffness.rms_residual_rad * kArcsecPerRad}}}};
}

}  // namespace wavebench::metrology
