#include "wavebench/metrology/static_te_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include "wavebench/metrology/figure_propagation.hpp"

namespace wavebench::metrology {

const char* direction_name(Direction direction) {
  return direction == Direction::kForward ? "forward" : "reverse";
}

UncertainFigure static_point_uncertainty(double te_arcmin, double te_noise_rad,
                                         const StaticTeUncertaintyInputs& inputs,
                                         const GearSense& sense) {
  UncertainFigure f;
  f.value = te_arcmin;
  // The output encoder's step is fixed by its counts, and so is the drive's at the same targets:
  // the same in every repeat. The window noise and where the output settled are not.
  if (inputs.output_resolution_rad > 0) {
    f.add("output encoder quantisation",
          quantisation_standard(inputs.output_resolution_rad) * kArcminPerRad);
  }
  if (inputs.input_resolution_rad > 0) {
    f.add("input encoder quantisation (/N)",
          quantisation_standard(inputs.input_resolution_rad / sense.ratio) * kArcminPerRad);
  }
  f.add("noise after window averaging", te_noise_rad * kArcminPerRad, 'A', true);
  if (inputs.settle_drift_rad > 0) {
    f.add("settle criterion", rectangular_standard(inputs.settle_drift_rad / 2) * kArcminPerRad,
          'B', true);
  }
  return f;
}

StaticTePointResult static_point_result(const StaticTePoint& p, const GearSense& sense,
                                        const StaticTeUncertaintyInputs& inputs) {
  StaticTePointResult r;
  r.position = p.position;
  // Within one output revolution: the output encoder's multi-turn zero is arbitrary (the
  // simulated one sits at 2048 turns), so whole turns carry no information here.
  const double deg = sense.model_output_angle(p.theta_out_rad) * 180.0 / std::numbers::pi;
  r.output_angle_deg = deg - 360.0 * std::floor(deg / 360.0);
  r.te_arcmin = sense.transmission_error(p.theta_in_rad, p.theta_out_rad) * kArcminPerRad;
  r.torque_nm = p.torque_nm;
  r.te = static_point_uncertainty(r.te_arcmin, p.te_noise_rad, inputs, sense);
  return r;
}

StaticTeSummary summarise_static_pass(const StaticTePass& pass, const GearSense& sense,
                                      const StaticTeUncertaintyInputs& uncertainty) {
  sense.validate();
  if (pass.points.empty()) {
    throw std::invalid_argument(std::string("static TE pass (") + direction_name(pass.direction) +
                                ", load_nm " + std::to_string(pass.load_nm) +
                                ") has no points; expected one per position");
  }
  StaticTeSummary s;
  s.direction = pass.direction;
  s.load_nm = pass.load_nm;
  double sum = 0, torque = 0;
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& p : pass.points) {
    const auto r = static_point_result(p, sense, uncertainty);
    sum += r.te_arcmin;
    torque += p.torque_nm;
    lo = std::min(lo, r.te_arcmin);
    hi = std::max(hi, r.te_arcmin);
    s.points.push_back(r);
  }
  const double n = static_cast<double>(s.points.size());
  s.mean_arcmin = sum / n;
  s.mean_torque_nm = torque / n;
  s.p2p_arcmin = hi - lo;
  double squares = 0;
  for (const auto& r : s.points)
    squares += (r.te_arcmin - s.mean_arcmin) * (r.te_arcmin - s.mean_arcmin);
  s.std_arcmin = std::sqrt(squares / n);
  std::vector<UncertainFigure> te;
  for (const auto& r : s.points) te.push_back(r.te);
  s.mean = mean_of(te);
  s.p2p = peak_to_peak_of(te);
  s.std = population_std_of(te);
  return s;
}

StaticTeResult analyse_static_te(std::span<const StaticTePass> passes, const GearSense& sense,
                                 const StaticTeUncertaintyInputs& uncertainty) {
  StaticTeResult result;
  for (const auto& pass : passes) {
    result.passes.push_back(summarise_static_pass(pass, sense, uncertainty));
  }

  // Lost motion: forward and reverse passes at the same load, matched by position.
  for (const auto& fwd : result.passes) {
    if (fwd.direction != Direction::kForward) continue;
    for (const auto& rev : result.passes) {
      if (rev.direction != Direction::kReverse || rev.load_nm != fwd.load_nm) continue;
      std::map<int, const StaticTePointResult*> reverse_te;
      for (const auto& p : rev.points) reverse_te[p.position] = &p;
      LostMotionProfile lm;
      lm.load_nm = fwd.load_nm;
      double sum = 0;
      lm.max_arcmin = -INFINITY;
      for (const auto& p : fwd.points) {
        const auto it = reverse_te.find(p.position);
        if (it == reverse_te.end()) continue;
        // The width between the directions, a positive number (bench.md §4): under a brake
        // forward TE falls below reverse TE, unloaded the backlash may leave it either side.
        const double v = std::abs(p.te_arcmin - it->second->te_arcmin);
        lm.positions.push_back(p.position);
        lm.lost_motion_arcmin.push_back(v);
        lm.per_position.push_back(absolute_of(difference_of(p.te, it->second->te)));
        sum += v;
        lm.max_arcmin = std::max(lm.max_arcmin, v);
        lm.max_abs_arcmin = std::max(lm.max_abs_arcmin, std::abs(v));
      }
      if (lm.positions.empty()) continue;
      lm.mean_arcmin = sum / static_cast<double>(lm.positions.size());
      lm.mean = mean_of(lm.per_position);
      lm.max = maximum_of(lm.per_position);
      std::vector<UncertainFigure> widths;
      for (const auto& f : lm.per_position) widths.push_back(absolute_of(f));
      lm.max_abs = maximum_of(widths);
      result.lost_motion.push_back(lm);
      break;
    }
  }

  // Load shift against the lowest load of the same direction.
  for (Direction d : {Direction::kForward, Direction::kReverse}) {
    const StaticTeSummary* reference = nullptr;
    for (const auto& s : result.passes) {
      if (s.direction == d && (!reference || s.load_nm < reference->load_nm)) reference = &s;
    }
    if (!reference) continue;
    for (const auto& s : result.passes) {
      if (s.direction != d || &s == reference || s.load_nm == reference->load_nm) continue;
      LoadShift shift;
      shift.direction = d;
      shift.load_nm = s.load_nm;
      shift.reference_load_nm = reference->load_nm;
      shift.shift_arcmin = s.mean_arcmin - reference->mean_arcmin;
      shift.shift = difference_of(s.mean, reference->mean);
      if (shift.shift_arcmin != 0) {
        // The torque the gear held, where measured: a brake holds the output with less than
        // its setting once the output has come to rest (it also decelerated it). A brake only
        // resists, so forward and reverse shift in opposite senses; K is a magnitude.
        double torque = s.load_nm - reference->load_nm;
        const double held = s.mean_torque_nm - reference->mean_torque_nm;
        if (std::isfinite(held) && held != 0) torque = held;
        shift.stiffness_nm_per_rad =
            std::abs(torque) / std::abs(shift.shift_arcmin / kArcminPerRad);
        // K = T/|s|: u(K)/K = u(s)/|s| per source (the held torque's own noise, averaged over
        // the windows, is far below the shift's and left out).
        auto k = scaled(shift.shift, *shift.stiffness_nm_per_rad / std::abs(shift.shift_arcmin));
        k.value = *shift.stiffness_nm_per_rad;
        shift.stiffness = k;
      }
      result.load_shifts.push_back(shift);
    }
  }
  return result;
}

nlohmann::json to_json(const StaticTeResult& result) {
  nlohmann::json j;
  j["static"] = nlohmann::json::array();
  for (const auto& s : result.passes) {
    nlohmann::json points = nlohmann::json::array();
    for (const auto& p : s.points) {
      points.push_back({{"position", p.position},
                        {"output_angle_deg", p.output_angle_deg},
                        {"te_arcmin", p.te_arcmin},
                        {"torque_nm", p.torque_nm},
                        {"uncertainty", {{"te_arcmin", to_json(p.te)}}}});
    }
    j["static"].push_back({{"direction", direction_name(s.direction)},
                           {"load_nm", s.load_nm},
                           {"mean_arcmin", s.mean_arcmin},
                           {"p2p_arcmin", s.p2p_arcmin},
                           {"std_arcmin", s.std_arcmin},
                           {"mean_torque_nm", s.mean_torque_nm},
                           {"uncertainty",
                            {{"mean_arcmin", to_json(s.mean)},
                             {"p2p_arcmin", to_json(s.p2p)},
                             {"std_arcmin", to_json(s.std)}}},
                           {"points", points}});
  }
  j["lost_motion"] = nlohmann::json::array();
  for (const auto& lm : result.lost_motion) {
    nlohmann::json per = nlohmann::json::array();
    for (const auto& f : lm.per_position) per.push_back(to_json(f));
    j["lost_motion"].push_back({{"load_nm", lm.load_nm},
                                {"positions", lm.positions},
                                {"lost_motion_arcmin", lm.lost_motion_arcmin},
                                {"mean_arcmin", lm.mean_arcmin},
                                {"max_arcmin", lm.max_arcmin},
                                {"max_abs_arcmin", lm.max_abs_arcmin},
                                {"uncertainty",
                                 {{"lost_motion_arcmin", per},
                                  {"mean_arcmin", to_json(lm.mean)},
                                  {"max_arcmin", to_json(lm.max)},
                                  {"max_abs_arcmin", to_json(lm.max_abs)}}}});
  }
  j["load_shift"] = nlohmann::json::array();
  for (const auto& s : result.load_shifts) {
    nlohmann::json u = {{"shift_arcmin", to_json(s.shift)}};
    if (s.stiffness) u["stiffness_nm_per_rad"] = to_json(*s.stiffness);
    j["load_shift"].push_back(
        {{"direction", direction_name(s.direction)},
         {"load_nm", s.load_nm},
         {"reference_load_nm", s.reference_load_nm},
         {"shift_arcmin", s.shift_arcmin},
         {"stiffness_nm_per_rad",
          s.stiffness_nm_per_rad ? nlohmann::json(*s.stiffness_nm_per_rad) : nlohmann::json()},
         {"uncertainty", u}});
  }
  return j;
}

}  // namespace wavebench::metrology
