#include "wavebench/procedures/static_te_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

namespace wavebench::procedures {

const char* direction_name(Direction direction) {
  return direction == Direction::kForward ? "forward" : "reverse";
}

StaticTeSummary summarise_static_pass(const StaticTePass& pass, const GearSense& sense) {
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
    StaticTePointResult r;
    r.position = p.position;
    // Within one output revolution: the output encoder's multi-turn zero is arbitrary (the
    // simulated one sits at 2048 turns), so whole turns carry no information here.
    const double deg = sense.model_output_angle(p.theta_out_rad) * 180.0 / std::numbers::pi;
    r.output_angle_deg = deg - 360.0 * std::floor(deg / 360.0);
    r.te_arcmin = sense.transmission_error(p.theta_in_rad, p.theta_out_rad) * kArcminPerRad;
    r.torque_nm = p.torque_nm;
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
  return s;
}

StaticTeResult analyse_static_te(std::span<const StaticTePass> passes, const GearSense& sense) {
  StaticTeResult result;
  for (const auto& pass : passes) result.passes.push_back(summarise_static_pass(pass, sense));

  // Lost motion: forward and reverse passes at the same load, matched by position.
  for (const auto& fwd : result.passes) {
    if (fwd.direction != Direction::kForward) continue;
    for (const auto& rev : result.passes) {
      if (rev.direction != Direction::kReverse || rev.load_nm != fwd.load_nm) continue;
      std::map<int, double> reverse_te;
      for (const auto& p : rev.points) reverse_te[p.position] = p.te_arcmin;
      LostMotionProfile lm;
      lm.load_nm = fwd.load_nm;
      double sum = 0;
      lm.max_arcmin = -INFINITY;
      for (const auto& p : fwd.points) {
        const auto it = reverse_te.find(p.position);
        if (it == reverse_te.end()) continue;
        // The width between the directions, a positive number (bench.md §4): under a brake
        // forward TE falls below reverse TE, unloaded the backlash may leave it either side.
        const double v = std::abs(it->second - p.te_arcmin);
        lm.positions.push_back(p.position);
        lm.lost_motion_arcmin.push_back(v);
        sum += v;
        lm.max_arcmin = std::max(lm.max_arcmin, v);
      }
      if (lm.positions.empty()) continue;
      lm.mean_arcmin = sum / static_cast<double>(lm.positions.size());
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
      if (shift.shift_arcmin != 0) {
        // The torque the gear held, where measured: a brake holds the output with less than
        // its setting once the output has come to rest (it also decelerated it). A brake only
        // resists, so forward and reverse shift in opposite senses; K is a magnitude.
        double torque = s.load_nm - reference->load_nm;
        const double held = s.mean_torque_nm - reference->mean_torque_nm;
        if (std::isfinite(held) && held != 0) torque = held;
        shift.stiffness_nm_per_rad =
            std::abs(torque) / std::abs(shift.shift_arcmin / kArcminPerRad);
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
                        {"torque_nm", p.torque_nm}});
    }
    j["static"].push_back({{"direction", direction_name(s.direction)},
                           {"load_nm", s.load_nm},
                           {"mean_arcmin", s.mean_arcmin},
                           {"p2p_arcmin", s.p2p_arcmin},
                           {"std_arcmin", s.std_arcmin},
                           {"mean_torque_nm", s.mean_torque_nm},
                           {"points", points}});
  }
  j["lost_motion"] = nlohmann::json::array();
  for (const auto& lm : result.lost_motion) {
    j["lost_motion"].push_back({{"load_nm", lm.load_nm},
                                {"positions", lm.positions},
                                {"lost_motion_arcmin", lm.lost_motion_arcmin},
                                {"mean_arcmin", lm.mean_arcmin},
                                {"max_arcmin", lm.max_arcmin}});
  }
  j["load_shift"] = nlohmann::json::array();
  for (const auto& s : result.load_shifts) {
    j["load_shift"].push_back(
        {{"direction", direction_name(s.direction)},
         {"load_nm", s.load_nm},
         {"reference_load_nm", s.reference_load_nm},
         {"shift_arcmin", s.shift_arcmin},
         {"stiffness_nm_per_rad",
          s.stiffness_nm_per_rad ? nlohmann::json(*s.stiffness_nm_per_rad) : nlohmann::json()}});
  }
  return j;
}

}  // namespace wavebench::procedures
