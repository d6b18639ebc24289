#include "wavebench/metrology/torsional_loop.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "wavebench/metrology/gear_sense.hpp"

namespace wavebench::metrology {

namespace {

struct SidePoint {
  double torque = 0, twist = 0, torque_u = 0, twist_u = 0;
};

bool rising(LoopBranch b) {
  return b != LoopBranch::kUnloading;
}

// The used points of the rising (or falling) branch on one side of zero torque beyond the
// zero band, sorted by torque. The rising branch below zero is the reloading alone: the first
// loading starts wherever the gear was left and only its way up from zero belongs to the loop.
std::vector<SidePoint> side_points(std::span<const LoopPoint> points, bool rising_branch, int side,
                                   double band) {
  std::vector<SidePoint> out;
  for (const auto& p : points) {
    if (p.voided || rising(p.branch) != rising_branch) continue;
    if (p.branch == LoopBranch::kFirstLoading && side < 0) continue;
    if (side * p.torque_nm <= band) continue;
    out.push_back({p.torque_nm, p.twist_rad, p.torque_standard_nm, p.twist_standard_rad});
  }
  std::sort(out.begin(), out.end(),
            [](const SidePoint& a, const SidePoint& b) { return a.torque < b.torque; });
  return out;
}

std::string branch_side(bool rising_branch, int side) {
  return std::string(rising_branch ? "rising" : "falling") + " branch at " +
         (side > 0 ? "positive" : "negative") + " torque";
}

// A straight line (least squares) through the k points nearest in torque to t0, read at t0;
// its noise from each point's noise after averaging (twist, and torque through the slope).
struct LocalValue {
  double value = 0, slope = 0, noise_variance = 0;
};

LocalValue local_line(const std::vector<SidePoint>& pts, double t0, int k,
                      const std::string& what) {
  if (pts.size() < 2) {
    throw std::invalid_argument("torsional loop: the " + what + " has " +
                                std::to_string(pts.size()) +
                                " points beyond the zero band; expected at least 2");
  }
  std::vector<std::size_t> order(pts.size());
  std::iota(order.begin(), order.end(), 0);
  const auto n = std::min<std::size_t>(static_cast<std::size_t>(std::max(k, 2)), pts.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n), order.end(),
                    [&](std::size_t a, std::size_t b) {
                      return std::abs(pts[a].torque - t0) < std::abs(pts[b].torque - t0);
                    });
  order.resize(n);
  double tm = 0, ym = 0;
  for (auto i : order) {
    tm += pts[i].torque;
    ym += pts[i].twist;
  }
  tm /= static_cast<double>(n);
  ym /= static_cast<double>(n);
  double sxx = 0, sxy = 0;
  for (auto i : order) {
    sxx += (pts[i].torque - tm) * (pts[i].torque - tm);
    sxy += (pts[i].torque - tm) * (pts[i].twist - ym);
  }
  LocalValue v;
  v.slope = sxx > 0 ? sxy / sxx : 0;
  v.value = ym + v.slope * (t0 - tm);
  for (auto i : order) {
    const double w =
        1.0 / static_cast<double>(n) + (sxx > 0 ? (pts[i].torque - tm) * (t0 - tm) / sxx : 0.0);
    v.noise_variance +=
        w * w *
        (pts[i].twist_u * pts[i].twist_u + v.slope * v.slope * pts[i].torque_u * pts[i].torque_u);
  }
  return v;
}

// Twist of a branch at torque t by linear interpolation between its bracketing points; none
// outside the points' torque range.
std::optional<double> interpolate(const std::vector<SidePoint>& pts, double t) {
  if (pts.empty() || t < pts.front().torque || t > pts.back().torque) return std::nullopt;
  const auto it = std::lower_bound(pts.begin(), pts.end(), t,
                                   [](const SidePoint& p, double x) { return p.torque < x; });
  if (it == pts.begin()) return it->twist;
  const auto& hi = *it;
  const auto& lo = *(it - 1);
  if (hi.torque == lo.torque) return 0.5 * (hi.twist + lo.twist);
  return lo.twist + (t - lo.torque) / (hi.torque - lo.torque) * (hi.twist - lo.twist);
}

// How far the input-order TE terms can move the twist while the input turns by `span_in`:
// each term by at most its slope times the span, and never more than its peak-to-peak.
double kinematic_change(const LoopSensors& s, double span_in) {
  double sum = 0;
  for (const auto& t : s.input_terms) {
    const double a = std::abs(t.amplitude_rad);
    const double d = std::min(2 * a, a * std::abs(t.order_input) * std::abs(span_in));
    sum += d * d;
  }
  return std::sqrt(sum);
}

double twist_step_standard(double step) {
  return quantisation_standard(step);
}

// A Type B term enters the budget where the bench has it (an unknown resolution, no input-order
// TE terms: nothing to list).
void add_b(UncertainFigure& f, const char* source, double standard) {
  if (standard > 0 && std::isfinite(standard)) f.add(source, standard);
}

// A width made of local readings: value = Σ coefficient·reading.
struct Reading {
  LocalValue value;
  double coefficient;
};

UncertainFigure width_figure(std::initializer_list<Reading> readings, const LoopSensors& s) {
  UncertainFigure f;
  double noise = 0, norm = 0, torque_sensitivity = 0;
  for (const auto& r : readings) {
    f.value += r.coefficient * r.value.value;
    noise += r.coefficient * r.coefficient * r.value.noise_variance;
    norm += r.coefficient * r.coefficient;
    torque_sensitivity += r.coefficient * r.coefficient * r.value.slope * r.value.slope;
  }
  norm = std::sqrt(norm);
  f.add("noise after averaging", std::sqrt(noise), 'A');
  add_b(f, "output encoder quantisation", norm * twist_step_standard(s.output_encoder_step_rad));
  add_b(f, "input encoder quantisation",
        norm * twist_step_standard(s.ratio > 0 ? s.input_encoder_step_rad / s.ratio : 0));
  add_b(f, "torque sensor quantisation",
        std::sqrt(torque_sensitivity) * quantisation_standard(s.torque_step_nm));
  // The input turns by N times the width between the two ends of it.
  add_b(f, "kinematic TE while the input turns",
        rectangular_standard(kinematic_change(s, s.ratio * std::abs(f.value))));
  return f;
}

}  // namespace

const char* loop_branch_name(LoopBranch branch) {
  switch (branch) {
    case LoopBranch::kFirstLoading:
      return "first_loading";
    case LoopBranch::kUnloading:
      return "unloading";
    case LoopBranch::kReloading:
      break;
  }
  return "reloading";
}

void TorsionalLoopOptions::validate() const {
  const auto fail = [](const char* key, double v, const char* expected) {
    throw std::invalid_argument(std::string("torsional.") + key + " = " + std::to_string(v) +
                                "; expected " + expected);
  };
  if (!(rated_torque_nm > 0)) fail("rated_torque_nm", rated_torque_nm, "> 0");
  if (!(lost_motion_fraction > 0 && lost_motion_fraction < 1)) {
    fail("lost_motion_fraction", lost_motion_fraction, "between 0 and 1 (0.03 for ±3 %)");
  }
  if (!(zero_band_nm >= 0)) fail("zero_band_nm", zero_band_nm, ">= 0");
  if (local_points < 2) fail("local_points", local_points, ">= 2");
  if (breakpoint_grid < 4) fail("breakpoint_grid", breakpoint_grid, ">= 4");
}

TorsionalLoopResult analyse_torsional_loop(std::span<const LoopPoint> points,
                                           const LoopSensors& sensors,
                                           const TorsionalLoopOptions& options) {
  options.validate();
  TorsionalLoopResult r;
  const double band = options.zero_band_nm;
  for (const auto& p : points) {
    if (p.voided) {
      ++r.points_voided;
      continue;
    }
    ++r.points_used;
    if (std::abs(p.torque_nm) <= band) ++r.flat_step_points;
    r.peak_torque_nm = std::max(r.peak_torque_nm, p.torque_nm);
    r.valley_torque_nm = std::min(r.valley_torque_nm, p.torque_nm);
  }
  const auto rise_above = side_points(points, true, +1, band);
  const auto rise_below = side_points(points, true, -1, band);
  const auto fall_above = side_points(points, false, +1, band);
  const auto fall_below = side_points(points, false, -1, band);
  const int k = options.local_points;

  // Zero torque reached from either side, on each branch.
  const auto ra0 = local_line(rise_above, 0, k, branch_side(true, +1));
  const auto rb0 = local_line(rise_below, 0, k, branch_side(true, -1));
  const auto fa0 = local_line(fall_above, 0, k, branch_side(false, +1));
  const auto fb0 = local_line(fall_below, 0, k, branch_side(false, -1));
  r.rising_zero_from_above_rad = ra0.value;
  r.rising_zero_from_below_rad = rb0.value;
  r.unloading_zero_from_above_rad = fa0.value;
  r.unloading_zero_from_below_rad = fb0.value;

  // Hysteresis loss: unloaded from +T_max to zero, against reloaded from −T_max to zero.
  r.hysteresis_loss_rad = width_figure({{fa0, 1.0}, {rb0, -1.0}}, sensors);
  // Backlash: the flat step of each branch at zero torque, the mean of the two.
  r.backlash_rad = width_figure({{ra0, 0.5}, {rb0, -0.5}, {fa0, 0.5}, {fb0, -0.5}}, sensors);
  // Lost motion: between the loop's mid-points at ±x % of rated.
  const double x = options.lost_motion_fraction * options.rated_torque_nm;
  r.lost_motion_torque_nm = x;
  const auto rax = local_line(rise_above, x, k, branch_side(true, +1));
  const auto fax = local_line(fall_above, x, k, branch_side(false, +1));
  const auto rbx = local_line(rise_below, -x, k, branch_side(true, -1));
  const auto fbx = local_line(fall_below, -x, k, branch_side(false, -1));
  r.lost_motion_rad = width_figure({{rax, 0.5}, {fax, 0.5}, {rbx, -0.5}, {fbx, -0.5}}, sensors);

  // The mean curve: at each measured torque, the mid-point between the point and the other
  // branch interpolated there. The side of zero is the fit's "travel": its offsets are where
  // the mean curve meets zero torque from above and from below.
  std::vector<TorqueTwistPoint> mean;
  for (int side : {+1, -1}) {
    const auto& rise = side > 0 ? rise_above : rise_below;
    const auto& fall = side > 0 ? fall_above : fall_below;
    for (const auto* pair : {&rise, &fall}) {
      const auto& other = pair == &rise ? fall : rise;
      for (const auto& p : *pair) {
        if (const auto o = interpolate(other, p.torque)) {
          mean.push_back({p.torque, 0.5 * (p.twist + *o), side});
        }
      }
    }
  }
  std::sort(mean.begin(), mean.end(), [](const TorqueTwistPoint& a, const TorqueTwistPoint& b) {
    return a.torque_nm < b.torque_nm;
  });
  for (const auto& m : mean) {
    r.mean_torque_nm.push_back(m.torque_nm);
    r.mean_twist_rad.push_back(m.twist_rad);
  }
  const auto fit = fit_three_segment(mean, options.breakpoint_grid);
  r.fit_rms_residual_rad = fit.stiffness.rms_residual_rad;

  double mean_peak = 0;
  for (const auto& m : mean) mean_peak = std::max(mean_peak, std::abs(m.torque_nm));
  const double c[3] = {1 / fit.stiffness.k1, 1 / fit.stiffness.k2, 1 / fit.stiffness.k3};
  const double segment[3] = {fit.stiffness.t1, fit.stiffness.t2 - fit.stiffness.t1,
                             mean_peak - fit.stiffness.t2};
  const double q_out = twist_step_standard(sensors.output_encoder_step_rad);
  const double q_in =
      twist_step_standard(sensors.ratio > 0 ? sensors.input_encoder_step_rad / sensors.ratio : 0);
  const double q_t = quantisation_standard(sensors.torque_step_nm);
  UncertainFigure* ks[3] = {&r.k1_nm_per_rad, &r.k2_nm_per_rad, &r.k3_nm_per_rad};
  for (int i = 0; i < 3; ++i) {
    UncertainFigure& f = *ks[i];
    const double kk = 1 / c[i];
    f.value = kk;
    f.add("fit residual", kk * kk * fit.compliance_standard[i], 'A');
    // A segment's compliance is a twist span over a torque span, each end read once.
    const double dt = std::max(segment[i], 1e-12);
    add_b(f, "output encoder quantisation", kk * kk * std::sqrt(2.0) * q_out / dt);
    add_b(f, "input encoder quantisation", kk * kk * std::sqrt(2.0) * q_in / dt);
    add_b(f, "torque sensor quantisation", kk * std::sqrt(2.0) * q_t / dt);
    const double w = dt * c[i];  // the segment's twist span
    add_b(f, "kinematic TE while the input turns",
          kk * rectangular_standard(kinematic_change(sensors, sensors.ratio * w)) / w);
  }
  UncertainFigure* ts[2] = {&r.t1_nm, &r.t2_nm};
  const double t_value[2] = {fit.stiffness.t1, fit.stiffness.t2};
  const double t_profile[2] = {fit.t1_standard_nm, fit.t2_standard_nm};
  for (int i = 0; i < 2; ++i) {
    UncertainFigure& f = *ts[i];
    f.value = t_value[i];
    f.add("fit residual (profile)", t_profile[i], 'A');
    // A twist error δ at the kink moves the crossing of the two segments by δ/|c_i − c_i+1|.
    const double dc = std::abs(c[i] - c[i + 1]);
    if (dc > 0) {
      add_b(f, "output encoder quantisation", std::sqrt(2.0) * q_out / dc);
      add_b(f, "input encoder quantisation", std::sqrt(2.0) * q_in / dc);
    }
  }
  return r;
}

namespace {

// The fitted three-segment curve, plot-ready (issue #23): each side of zero at the mean curve's
// own offset (its median residual about the fitted compliance), 101 points from zero to the
// side's largest torque. Computed once here; the report and the run page only draw it.
nlohmann::json fit_curve_json(const TorsionalLoopResult& r) {
  ThreeSegmentStiffness k;
  k.k1 = r.k1_nm_per_rad.value;
  k.k2 = r.k2_nm_per_rad.value;
  k.k3 = r.k3_nm_per_rad.value;
  k.t1 = r.t1_nm.value;
  k.t2 = r.t2_nm.value;
  nlohmann::json sides = nlohmann::json::array();
  if (!(k.k1 > 0 && k.k2 > 0 && k.k3 > 0)) return sides;
  const std::size_t n = std::min(r.mean_torque_nm.size(), r.mean_twist_rad.size());
  for (const int side : {+1, -1}) {
    std::vector<double> offsets;
    double t_end = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double torque = r.mean_torque_nm[i];
      if (side * torque <= 0) continue;
      offsets.push_back((r.mean_twist_rad[i] - k.twist_at(torque)) * kArcminPerRad);
      t_end = std::max(t_end, std::abs(torque));
    }
    if (offsets.empty()) continue;
    std::nth_element(offsets.begin(), offsets.begin() + offsets.size() / 2, offsets.end());
    const double offset = offsets[offsets.size() / 2];
    nlohmann::json torque = nlohmann::json::array(), twist = nlohmann::json::array();
    for (int i = 0; i <= 100; ++i) {
      const double t = side * t_end * i / 100.0;
      torque.push_back(t);
      twist.push_back(offset + k.twist_at(t) * kArcminPerRad);
    }
    sides.push_back({{"side", side > 0 ? "positive" : "negative"},
                     {"offset_arcmin", offset},
                     {"torque_nm", torque},
                     {"twist_arcmin", twist}});
  }
  return sides;
}

}  // namespace

nlohmann::json to_json(const TorsionalLoopResult& r) {
  const double arcmin = kArcminPerRad;
  nlohmann::json mean_twist = nlohmann::json::array();
  for (double t : r.mean_twist_rad) mean_twist.push_back(t * arcmin);
  return {{"hysteresis_loss_arcmin", to_json(r.hysteresis_loss_rad, arcmin)},
          {"lost_motion_arcmin", to_json(r.lost_motion_rad, arcmin)},
          {"lost_motion_torque_nm", r.lost_motion_torque_nm},
          {"backlash_arcmin", to_json(r.backlash_rad, arcmin)},
          {"stiffness",
           {{"k1_nm_per_rad", to_json(r.k1_nm_per_rad)},
            {"k2_nm_per_rad", to_json(r.k2_nm_per_rad)},
            {"k3_nm_per_rad", to_json(r.k3_nm_per_rad)},
            {"t1_nm", to_json(r.t1_nm)},
            {"t2_nm", to_json(r.t2_nm)},
            {"rms_residual_arcsec", r.fit_rms_residual_rad * kArcsecPerRad}}},
          {"zero_torque_twist_arcmin",
           {{"unloading_from_above", r.unloading_zero_from_above_rad * arcmin},
            {"unloading_from_below", r.unloading_zero_from_below_rad * arcmin},
            {"rising_from_above", r.rising_zero_from_above_rad * arcmin},
            {"rising_from_below", r.rising_zero_from_below_rad * arcmin}}},
          {"peak_torque_nm", r.peak_torque_nm},
          {"valley_torque_nm", r.valley_torque_nm},
          {"points_used", r.points_used},
          {"points_voided", r.points_voided},
          {"flat_step_points", r.flat_step_points},
          {"mean_curve", {{"torque_nm", r.mean_torque_nm}, {"twist_arcmin", mean_twist}}},
          {"fit_curve", fit_curve_json(r)}};
}

}  // namespace wavebench::metrology
