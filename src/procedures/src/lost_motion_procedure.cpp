#include "wavebench/procedures/lost_motion_procedure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "wavebench/metrology/figure_propagation.hpp"
#include "wavebench/metrology/gear_sense.hpp"
#include "wavebench/procedures/dynamic_te_procedure.hpp"
#include "wavebench/procedures/option_reader.hpp"
#include "wavebench/procedures/sample_recorder.hpp"

namespace wavebench::procedures {

namespace {

// Stay below the brake's own limit and the safety limit, with a margin for the brake's
// torque ripple.
double ladder_cap_nm(const bench::BenchDescription& d) {
  double cap = std::numeric_limits<double>::infinity();
  for (double limit : {d.max_brake_torque_nm, d.limits.max_brake_torque_nm}) {
    if (limit > 0) cap = std::min(cap, 0.95 * limit);
  }
  return cap;
}

// Twist and torque averaged over the samples whose output angle lies in [lo, hi].
metrology::TorqueTwistPoint window_average(const std::vector<storage::SyncSample>& samples,
                                            const metrology::GearSense& sense, double lo,
                                            double hi, int travel, double torque_nm,
                                            std::vector<double>& noise_rad) {
  double twist = 0, torque = 0;
  int angles = 0, torques = 0;
  std::vector<double> twists;
  for (const auto& s : samples) {
    if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid)) continue;
    const double theta2 = sense.model_output_angle(s.theta_out_rad);
    if (theta2 < lo || theta2 > hi) continue;
    twist -= sense.transmission_error(s.theta_in_rad, s.theta_out_rad);
    twists.push_back(-sense.transmission_error(s.theta_in_rad, s.theta_out_rad));
    ++angles;
    if (s.valid(storage::kTorqueValid)) {
      torque += sense.direction_sign * s.torque_nm;
      ++torques;
    }
  }
  if (angles < 8 || torques == 0) {
    std::ostringstream m;
    m << "lost motion: only " << angles << " samples in the output window at " << torque_nm
      << " N·m (" << (travel > 0 ? "forward" : "reverse")
      << "); expected the output to slip through it (raise run_in_output_rad or the torque "
         "ladder's cap)";
    throw std::runtime_error(m.str());
  }
  // The twist moves with the TE over the window: its noise from second differences, white.
  noise_rad.push_back(metrology::sample_noise_from_second_differences(twists) /
                      std::sqrt(static_cast<double>(angles)));
  return {torque / torques, twist / angles, travel};
}

// The brake torques of the ladder, ascending: the explicit list or the fractions of rated,
// without those above the brake's own limit and the safety limit (crossing one trips the
// bench). Throws std::invalid_argument when rated is unknown for fractions.
std::vector<double> torque_ladder(const LostMotionOptions& o, const bench::BenchDescription& d) {
  std::vector<double> ladder;
  if (o.torques_nm.empty()) {
    if (!(d.rated_torque_nm > 0)) {
      throw std::invalid_argument(
          "lost-motion: the bench's rated_torque is " + std::to_string(d.rated_torque_nm) +
          "; expected > 0 for a ladder in fractions of it (or give torques_nm)");
    }
    for (double f : o.torque_fractions) ladder.push_back(f * d.rated_torque_nm);
  } else {
    ladder = o.torques_nm;
  }
  std::erase_if(ladder, [cap = ladder_cap_nm(d)](double t) { return t > cap; });
  std::sort(ladder.begin(), ladder.end());
  return ladder;
}

std::string short_ladder_message(std::size_t rungs, const bench::BenchDescription& d) {
  return "lost-motion: " + std::to_string(rungs) + " ladder torques below the brake limit " +
         std::to_string(ladder_cap_nm(d)) + " N·m; expected at least 4";
}

}  // namespace

namespace {

// The one declaration of the options: parses them, and describes them for the schema. Ladder
// torques are > 0: a brake at zero gives no torque sign to fit.
void declare(OptionReader& r, LostMotionOptions& o) {
  r.numbers("torque_fractions", o.torque_fractions, 0, 2, false, 4,
            {"", "brake torque ladder as fractions of the rated torque"});
  r.numbers("torques_nm", o.torques_nm, 0, 1e4, false, 4,
            {"N·m", "explicit brake torque ladder; overrides the fractions (empty: use them)"});
  r.number("input_speed_rad_s", o.input_speed_rad_s, 0, 1e4, false,
           {"rad/s", "input speed while twisting (slow)"});
  r.number("run_in_output_rad", o.run_in_output_rad, 0, 1, false,
           {"rad", "output travel before the window in each direction (takes up the twist)"});
  r.number("window_periods", o.window_periods, 0, 1000, false,
           {"", "mesh periods of the output averaged in each window"});
  r.number("lost_motion_fraction", o.lost_motion_fraction, 0, 1, false,
           {"", "lost motion is reported at ± this fraction of the rated torque"});
  r.number("brake_settle_s", o.brake_settle_s, 0, 600, true,
           {"s", "wait after a new brake torque"});
}

}  // namespace

std::vector<OptionSpec> LostMotionOptions::schema() {
  LostMotionOptions o;
  OptionReader r("lost-motion");
  declare(r, o);
  return r.described();
}

LostMotionOptions LostMotionOptions::from_json(const nlohmann::json& options) {
  LostMotionOptions o;
  nlohmann::json given = options;
  // An empty explicit ladder means "use the fractions" (configs/procedures/lost-motion.yaml).
  if (given.is_object() && given.contains("torques_nm") && given["torques_nm"].is_array() &&
      given["torques_nm"].empty()) {
    given.erase("torques_nm");
  }
  OptionReader r(given, "lost-motion", schema());
  declare(r, o);
  return o;
}

nlohmann::json LostMotionOptions::to_json() const {
  return {{"torque_fractions", torque_fractions},   {"torques_nm", torques_nm},
          {"input_speed_rad_s", input_speed_rad_s}, {"run_in_output_rad", run_in_output_rad},
          {"window_periods", window_periods},       {"lost_motion_fraction", lost_motion_fraction},
          {"brake_settle_s", brake_settle_s}};
}

namespace {

// Plot-ready (issue #23): each travel branch of the fitted model, twist = the fit's branch
// offset + φ(T), over the branch's torque span with zero torque. Computed once here; the
// report and the run page only draw it.
nlohmann::json fit_curve_json(const std::vector<metrology::TorqueTwistPoint>& record,
                              const metrology::LostMotionResult& result) {
  const auto& k = result.stiffness;
  nlohmann::json branches = nlohmann::json::array();
  if (!(k.k1 > 0 && k.k2 > 0 && k.k3 > 0)) return branches;
  for (const int travel : {+1, -1}) {
    double lo = 0, hi = 0;
    bool any = false;
    for (const auto& p : record) {
      if ((p.travel > 0 ? 1 : -1) != travel) continue;
      lo = std::min(lo, p.torque_nm);
      hi = std::max(hi, p.torque_nm);
      any = true;
    }
    if (!any) continue;
    const double offset = travel > 0 ? result.forward_offset_rad : result.reverse_offset_rad;
    nlohmann::json torque = nlohmann::json::array(), twist = nlohmann::json::array();
    for (int i = 0; i <= 200; ++i) {
      const double t = lo + (hi - lo) * i / 200.0;
      torque.push_back(t);
      twist.push_back((offset + k.twist_at(t)) * metrology::kArcminPerRad);
    }
    branches.push_back({{"travel", travel},
                        {"offset_arcmin", offset * metrology::kArcminPerRad},
                        {"torque_nm", torque},
                        {"twist_arcmin", twist}});
  }
  return branches;
}

}  // namespace

nlohmann::json LostMotionOutcome::to_json() const {
  nlohmann::json j = metrology::to_json(result);
  j["uncertainty"] = metrology::fit_uncertainty_json(uncertainty);
  j["stiffness"]["uncertainty"] = metrology::stiffness_uncertainty_json(uncertainty);
  j["rated_torque_nm"] = rated_torque_nm;
  j["ladder_nm"] = ladder_nm;
  nlohmann::json points = nlohmann::json::array();
  for (const auto& p : record) {
    points.push_back({{"travel", p.travel > 0 ? 1 : -1},
                      {"torque_nm", p.torque_nm},
                      {"twist_arcmin", p.twist_rad * metrology::kArcminPerRad}});
  }
  j["points"] = points;
  j["fit_curve"] = fit_curve_json(record, result);
  return j;
}

LostMotionProcedure::LostMotionProcedure(LostMotionOptions options)
    : options_(std::move(options)) {}

RunPlan LostMotionProcedure::plan(const bench::BenchDescription& bench) const {
  const auto& o = options_;
  bench.sense.validate();
  RunPlan plan;
  const auto ladder = torque_ladder(o, bench);
  if (ladder.size() < 4) plan.refusal = short_ladder_message(ladder.size(), bench);
  // Explicit torques are what the request asked for, all of them; fractions above the cap
  // are left out of the ladder by design and so never commanded.
  if (!o.torques_nm.empty()) {
    for (std::size_t i = 0; i < o.torques_nm.size(); ++i) {
      plan.brake_torques_nm.push_back(
          {"lost-motion.torques_nm[" + std::to_string(i) + "]", o.torques_nm[i], "N*m"});
    }
  } else {
    const double cap = ladder_cap_nm(bench);
    for (std::size_t i = 0; i < o.torque_fractions.size(); ++i) {
      if (o.torque_fractions[i] * bench.rated_torque_nm > cap) continue;
      plan.brake_torques_nm.push_back({"lost-motion.torque_fractions[" + std::to_string(i) + "]",
                                       o.torque_fractions[i], "x rated", bench.rated_torque_nm});
    }
  }
  plan.input_speeds_rad_s.push_back(
      {"lost-motion.input_speed_rad_s", o.input_speed_rad_s, "rad/s"});
  // As run(): at each rung the brake settles, then the input moves forward over the run-in
  // and the window and back.
  const auto teeth = gear_teeth(bench.twin_gear, bench.sense.ratio);
  const double window = o.window_periods * 2 * std::numbers::pi / teeth.z_flex;
  const double span_in = bench.sense.ratio * (2 * o.run_in_output_rad + window);
  const double rung_s = o.brake_settle_s + 2 * planned_move_s(span_in, o.input_speed_rad_s);
  plan.bench_time_s = static_cast<double>(ladder.size()) * rung_s;
  std::ostringstream terms;
  terms << ladder.size() << " ladder torques x " << rung_s
        << " s (lost-motion.brake_settle_s, two moves of " << span_in
        << " rad at lost-motion.input_speed_rad_s)";
  plan.duration_terms = terms.str();
  return plan;
}

LostMotionOutcome LostMotionProcedure::run(bench::Bench& bench,
                                           const ProcedureProgress& progress) const {
  const auto& o = options_;
  const auto& d = bench.description();
  const auto& sense = d.sense;
  sense.validate();
  LostMotionOutcome out;
  out.rated_torque_nm = d.rated_torque_nm;
  out.ladder_nm = torque_ladder(o, d);
  if (out.ladder_nm.size() < 4) {
    throw std::invalid_argument(short_ladder_message(out.ladder_nm.size(), d));
  }
  metrology::LostMotionOptions fit;
  fit.rated_torque_nm = d.rated_torque_nm > 0 ? d.rated_torque_nm : out.ladder_nm.back();
  fit.lost_motion_fraction = o.lost_motion_fraction;
  fit.validate();

  const auto teeth = gear_teeth(d.twin_gear, sense.ratio);
  const double window = o.window_periods * 2 * std::numbers::pi / teeth.z_flex;
  const double run_in = o.run_in_output_rad;
  const double start_in = bench.latest_sample().theta_in_rad;
  const double end_in = start_in + sense.ratio * (2 * run_in + window);
  const double lo = sense.model_output_angle(bench.latest_sample().theta_out_rad) + run_in;
  const double hi = lo + window;

  SampleRecorder recorder;
  ObserverRegistration registration(bench, recorder);
  std::vector<metrology::TorqueTwistPoint> forward, reverse;
  std::vector<double> forward_noise, reverse_noise;
  for (std::size_t i = 0; i < out.ladder_nm.size(); ++i) {
    const double t = out.ladder_nm[i];
    std::ostringstream phase;
    phase << "lost motion " << t << " N·m";
    if (progress) progress(phase.str(), static_cast<double>(i) / out.ladder_nm.size());
    bench.set_brake_torque(t);
    bench.wait_for(o.brake_settle_s);
    recorder.start();
    bench.move_input_to(end_in, o.input_speed_rad_s);
    recorder.stop();
    forward.push_back(window_average(recorder.samples(), sense, lo, hi, +1, t, forward_noise));
    recorder.start();
    bench.move_input_to(start_in, o.input_speed_rad_s);
    recorder.stop();
    reverse.push_back(window_average(recorder.samples(), sense, lo, hi, -1, t, reverse_noise));
  }
  bench.set_brake_torque(0);
  if (progress) progress("lost motion fit", 0.98);
  // The loop in the torque–twist plane: forward branch up the ladder, reverse branch from its
  // largest torque back down (torque ascending throughout).
  out.record = forward;
  out.record.insert(out.record.end(), reverse.rbegin(), reverse.rend());
  out.result = metrology::analyse_lost_motion(out.record, fit);
  metrology::LostMotionUncertaintyInputs inputs;
  inputs.input_resolution_rad = d.input_encoder_resolution_rad;
  inputs.output_resolution_rad = d.output_encoder_resolution_rad;
  inputs.ratio = sense.ratio;
  inputs.twist_noise_rad = forward_noise;
  inputs.twist_noise_rad.insert(inputs.twist_noise_rad.end(), reverse_noise.rbegin(),
                                reverse_noise.rend());
  out.uncertainty = metrology::lost_motion_uncertainty(out.record, fit, out.result, inputs);
  if (progress) progress("lost motion done", 1.0);
  return out;
}

}  // namespace wavebench::procedures
