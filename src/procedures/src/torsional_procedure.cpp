#include "wavebench/procedures/torsional_procedure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "wavebench/metrology/gear_sense.hpp"
#include "wavebench/procedures/option_reader.hpp"
#include "wavebench/procedures/sample_recorder.hpp"

namespace wavebench::procedures {

namespace {

using metrology::kArcminPerRad;
using metrology::LoopBranch;

// The smaller of the limits that are on (> 0); infinity when none is.
double tightest(std::initializer_list<double> limits) {
  double out = std::numeric_limits<double>::infinity();
  for (double l : limits) {
    if (l > 0) out = std::min(out, l);
  }
  return out;
}

double brake_limit_nm(const bench::BenchDescription& d) {
  return tightest({d.max_brake_torque_nm, d.limits.max_brake_torque_nm});
}

// The hold torque the options ask for on this bench (before any check).
double hold_torque(const TorsionalOptions& o, const bench::BenchDescription& d) {
  if (o.hold_torque_nm > 0) return o.hold_torque_nm;
  const double limit = brake_limit_nm(d);
  // A margin under the limit for the brake's own torque ripple (as the lost-motion ladder).
  return std::isfinite(limit) ? 0.95 * limit : 0.0;
}

std::string nm(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v << " N·m";
  return s.str();
}

// Twist of the twin's nominal gear at a torque [rad], for the plan's estimate only.
double nominal_twist(const model::GearParams& g, double torque) {
  if (const auto* s = std::get_if<model::ThreeSegmentStiffness>(&g.stiffness.law)) {
    if (s->k1 > 0 && s->k2 > 0 && s->k3 > 0) {
      const double t = std::abs(torque);
      return std::min(t, s->t1) / s->k1 + std::clamp(t - s->t1, 0.0, s->t2 - s->t1) / s->k2 +
             std::max(t - s->t2, 0.0) / s->k3;
    }
  }
  double k = g.stiffness.mean_stiffness.value_or(0);
  if (const auto* s = std::get_if<model::LinearPeriodicStiffness>(&g.stiffness.law)) k = s->k0;
  if (const auto* s = std::get_if<model::CubicStiffness>(&g.stiffness.law)) k = s->k1;
  // Without a usable stiffness the estimate takes a stiff gear of this class (1e5 N·m/rad).
  return std::abs(torque) / (k > 0 ? k : 1e5);
}

double reference_torque(const bench::BenchDescription& d, const TorsionalTorques& t) {
  return d.rated_torque_nm > 0 ? d.rated_torque_nm : t.t_max_nm;
}

// One averaged window: the gear's torque and twist in the model's sense, the output angle.
struct Window {
  double twist = 0, twist_std = 0, torque = 0, torque_std = 0;
  double theta2 = 0, theta2_range = 0, theta_in = 0;
  int samples = 0;
};

Window average(const std::vector<storage::SyncSample>& samples,
               const metrology::GearSense& sense) {
  Window w;
  double tw2 = 0, tq2 = 0;
  int torques = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& s : samples) {
    if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid)) continue;
    const double twist = -sense.transmission_error(s.theta_in_rad, s.theta_out_rad);
    const double theta2 = sense.model_output_angle(s.theta_out_rad);
    w.twist += twist;
    tw2 += twist * twist;
    w.theta2 += theta2;
    w.theta_in += s.theta_in_rad;
    lo = std::min(lo, theta2);
    hi = std::max(hi, theta2);
    ++w.samples;
    if (s.valid(storage::kTorqueValid)) {
      const double t = sense.direction_sign * s.torque_nm;
      w.torque += t;
      tq2 += t * t;
      ++torques;
    }
  }
  if (w.samples < 2 || torques < 2) {
    throw std::runtime_error("torsional: " + std::to_string(w.samples) + " samples with both " +
                             "angles and " + std::to_string(torques) +
                             " with torque in a window; expected at least 2 of each (window_s "
                             "too short for the SYNC period?)");
  }
  const double n = w.samples, m = torques;
  w.twist /= n;
  w.theta2 /= n;
  w.theta_in /= n;
  w.torque /= m;
  // Standard deviations of the means (noise after averaging).
  w.twist_std = std::sqrt(std::max(0.0, tw2 / n - w.twist * w.twist) * n / (n - 1) / n);
  w.torque_std = std::sqrt(std::max(0.0, tq2 / m - w.torque * w.torque) * m / (m - 1) / m);
  w.theta2_range = hi - lo;
  return w;
}

// The one declaration of the options: parses them, and describes them for the schema.
void declare(OptionReader& r, TorsionalOptions& o) {
  r.number("t_max_nm", o.t_max_nm, 0, 1e5, true,
           {"N·m",
            "peak torque of the loop (0: the unit's rated torque), reduced to stay under "
            "the hold torque by hold_margin"});
  r.number("hold_torque_nm", o.hold_torque_nm, 0, 1e5, true,
           {"N·m",
            "brake setting that locks the output (0: 95 % of the brake's and the "
            "safety limit)"});
  r.number("hold_margin", o.hold_margin, 0, 10, true,
           {"", "T_max stays below hold torque / (1 + this)"});
  r.number("twist_step_rad", o.twist_step_rad, 0, 0.01, false,
           {"rad", "output twist per input step (the input moves N times this)"});
  r.number("input_speed_rad_s", o.input_speed_rad_s, 0, 1e3, false,
           {"rad/s", "input speed of each step (slow)"});
  r.number("settle_s", o.settle_s, 0, 60, true, {"s", "wait after each step, before the window"});
  r.number("window_s", o.window_s, 0, 60, false,
           {"s", "twist and torque averaged over this at each step"});
  r.number("brake_settle_s", o.brake_settle_s, 0, 600, true,
           {"s", "wait after setting the hold torque"});
  r.number("lost_motion_fraction", o.lost_motion_fraction, 0, 0.5, false,
           {"", "lost motion is read at ± this fraction of the rated torque"});
  r.number("zero_band_fraction", o.zero_band_fraction, 0, 0.5, true,
           {"", "|torque| under this fraction of rated counts as zero (the flat step)"});
  r.number("slip_threshold_rad", o.slip_threshold_rad, 0, 0.1, false,
           {"rad", "output motion from where it was locked that voids a point (slip)"});
  r.integer("max_slipped_points", o.max_slipped_points, 0, 1000,
            {"", "more slipped points than this abort the run"});
  r.number("max_twist_rad", o.max_twist_rad, 0, 0.1, false,
           {"rad", "abort when T_max is not reached within this twist from the start"});
}

}  // namespace

std::vector<OptionSpec> TorsionalOptions::schema() {
  TorsionalOptions o;
  OptionReader r("torsional");
  declare(r, o);
  return r.described();
}

TorsionalOptions TorsionalOptions::from_json(const nlohmann::json& options) {
  TorsionalOptions o;
  OptionReader r(options, "torsional", schema());
  declare(r, o);
  return o;
}

nlohmann::json TorsionalOptions::to_json() const {
  return {{"t_max_nm", t_max_nm},
          {"hold_torque_nm", hold_torque_nm},
          {"hold_margin", hold_margin},
          {"twist_step_rad", twist_step_rad},
          {"input_speed_rad_s", input_speed_rad_s},
          {"settle_s", settle_s},
          {"window_s", window_s},
          {"brake_settle_s", brake_settle_s},
          {"lost_motion_fraction", lost_motion_fraction},
          {"zero_band_fraction", zero_band_fraction},
          {"slip_threshold_rad", slip_threshold_rad},
          {"max_slipped_points", max_slipped_points},
          {"max_twist_rad", max_twist_rad}};
}

nlohmann::json TorsionalOutcome::to_json() const {
  nlohmann::json j = metrology::to_json(result);
  j["rated_torque_nm"] = rated_torque_nm;
  j["t_max_nm"] = torques.t_max_nm;
  j["t_max_reason"] = torques.t_max_reason;
  j["hold_torque_nm"] = torques.hold_nm;
  j["slip"] = {{"threshold_arcmin", slip_threshold_rad * kArcminPerRad},
               {"slipped_points", slipped_points},
               {"max_output_moved_arcmin", max_output_moved_rad * kArcminPerRad}};
  nlohmann::json list = nlohmann::json::array();
  for (const auto& p : points) {
    list.push_back({{"branch", metrology::loop_branch_name(p.loop.branch)},
                    {"torque_nm", p.loop.torque_nm},
                    {"twist_arcmin", p.loop.twist_rad * kArcminPerRad},
                    {"output_moved_arcmin", p.output_moved_rad * kArcminPerRad},
                    {"voided", p.loop.voided}});
  }
  j["points"] = list;
  return j;
}

TorsionalProcedure::TorsionalProcedure(TorsionalOptions options) : options_(std::move(options)) {}

TorsionalTorques TorsionalProcedure::torques(const bench::BenchDescription& d) const {
  const auto& o = options_;
  TorsionalTorques t;
  const double brake_limit = brake_limit_nm(d);
  t.hold_nm = hold_torque(o, d);
  if (!(t.hold_nm > 0)) {
    throw std::invalid_argument(
        "torsional.hold_torque_nm: got '0', expected a torque > 0 (the bench names no brake "
        "limit to take 95 % of)");
  }
  if (t.hold_nm > brake_limit) {
    throw std::invalid_argument("torsional.hold_torque_nm: got '" + nm(t.hold_nm) +
                                "', expected at most " + nm(brake_limit) +
                                " (the bench's brake limit)");
  }
  double wanted = o.t_max_nm;
  std::string why = "t_max_nm " + nm(wanted) + " as given";
  if (!(wanted > 0)) {
    if (!(d.rated_torque_nm > 0)) {
      throw std::invalid_argument(
          "torsional.t_max_nm: got '0' on a bench without a rated torque, expected the loop's "
          "peak torque > 0 (or rated_torque in the bench config)");
    }
    wanted = d.rated_torque_nm;
    why = "the rated torque " + nm(wanted);
  }
  t.t_max_nm = wanted;
  t.t_max_reason = why;
  const double under_hold = t.hold_nm / (1 + o.hold_margin);
  if (t.t_max_nm > under_hold) {
    t.t_max_nm = under_hold;
    std::ostringstream s;
    s.precision(3);
    s << why << ", reduced to " << nm(under_hold) << " to stay " << 100 * o.hold_margin
      << " % under the brake's hold torque " << nm(t.hold_nm) << " (brake limit " << nm(brake_limit)
      << ")";
    t.t_max_reason = s.str();
  }
  if (d.limits.max_measured_torque_nm > 0 && t.t_max_nm > 0.9 * d.limits.max_measured_torque_nm) {
    t.t_max_nm = 0.9 * d.limits.max_measured_torque_nm;
    t.t_max_reason += ", reduced to " + nm(t.t_max_nm) + " (90 % of the safety limit " +
                      nm(d.limits.max_measured_torque_nm) + " on measured torque)";
  }
  const double x = o.lost_motion_fraction * reference_torque(d, t);
  if (!(t.t_max_nm >= 2 * x)) {
    throw std::invalid_argument("torsional: T_max " + nm(t.t_max_nm) + " (" + t.t_max_reason +
                                "), expected at least twice the lost-motion torque " + nm(x) +
                                " (raise hold_torque_nm or lower lost_motion_fraction)");
  }
  return t;
}

RunPlan TorsionalProcedure::plan(const bench::BenchDescription& bench) const {
  const auto& o = options_;
  bench.sense.validate();
  RunPlan plan;
  const double hold = hold_torque(o, bench);
  plan.brake_torques_nm.push_back({"torsional.hold_torque_nm", hold, "N*m"});
  plan.input_speeds_rad_s.push_back({"torsional.input_speed_rad_s", o.input_speed_rad_s, "rad/s"});
  double t_max = 0;
  try {
    t_max = torques(bench).t_max_nm;
  } catch (const std::invalid_argument& e) {
    plan.refusal = e.what();
  }
  // As run(): the brake settles and the lock is read, then steps of one twist step each over
  // the first loading (≈ twist at T_max), the unloading (twice it) and the reloading (once),
  // with the backlash crossed twice; each step a move, a settle and a window.
  const double twist = nominal_twist(bench.twin_gear, t_max);
  const double backlash = bench.twin_gear.backlash.total_rad;
  const double steps = std::ceil((4 * twist + 2 * backlash) / o.twist_step_rad);
  const double step_s = planned_move_s(bench.sense.ratio * o.twist_step_rad, o.input_speed_rad_s) +
                        o.settle_s + o.window_s;
  plan.bench_time_s = o.brake_settle_s + o.window_s + steps * step_s;
  std::ostringstream terms;
  terms << steps << " steps (4 x the nominal twist at T_max " << t_max
        << " N·m and 2 x backlash, in torsional.twist_step_rad) x " << step_s
        << " s (a move at torsional.input_speed_rad_s, torsional.settle_s, torsional.window_s)";
  plan.duration_terms = terms.str();
  return plan;
}

TorsionalOutcome TorsionalProcedure::run(bench::Bench& bench,
                                         const ProcedureProgress& progress) const {
  const auto& o = options_;
  const auto& d = bench.description();
  const auto& sense = d.sense;
  sense.validate();
  TorsionalOutcome out;
  out.torques = torques(d);
  out.rated_torque_nm = d.rated_torque_nm;
  out.slip_threshold_rad = o.slip_threshold_rad;
  const double t_max = out.torques.t_max_nm;
  const double reference = reference_torque(d, out.torques);
  const double zero_band = o.zero_band_fraction * reference;
  // Never beyond the safety limit on |TE| (its reference is the TE at connect).
  double max_twist = o.max_twist_rad;
  if (d.limits.max_te_excursion_rad > 0) {
    max_twist = std::min(max_twist, 0.8 * d.limits.max_te_excursion_rad);
  }

  SampleRecorder recorder;
  ObserverRegistration registration(bench, recorder);
  const auto measure = [&] {
    recorder.start();
    bench.wait_for(o.window_s);
    recorder.stop();
    return average(recorder.samples(), sense);
  };

  if (progress) progress("torsional: brake holds the output", 0);
  bench.set_brake_torque(out.torques.hold_nm);
  bench.wait_for(o.brake_settle_s);
  const Window start = measure();
  double locked_at = start.theta2;
  double target = start.theta_in;
  const double step_in = sense.ratio * o.twist_step_rad;

  // Steps the input in `dir` until `done(torque)`; every point recorded, slip voided.
  const auto branch = [&](LoopBranch b, int dir, const char* phase, double progress_from,
                          double progress_to, auto done, auto fraction) {
    for (;;) {
      target += dir * step_in;
      bench.move_input_to(target, o.input_speed_rad_s);
      bench.wait_for(o.settle_s);
      const Window w = measure();
      TorsionalPoint p;
      p.loop = {b, w.torque, w.twist, w.twist_std, w.torque_std, false};
      p.theta_in_rad = w.theta_in;
      p.theta2_rad = w.theta2;
      p.output_moved_rad = w.theta2 - locked_at;
      const double moved = std::max(std::abs(p.output_moved_rad), w.theta2_range);
      out.max_output_moved_rad = std::max(out.max_output_moved_rad, moved);
      if (moved > o.slip_threshold_rad) {
        p.loop.voided = true;
        ++out.slipped_points;
        locked_at = w.theta2;  // the brake holds again where the output came to rest
      }
      out.points.push_back(p);
      if (out.slipped_points > o.max_slipped_points) {
        std::ostringstream m;
        m.precision(3);
        m << "torsional: the output slipped at " << out.slipped_points << " points (the last by "
          << moved * kArcminPerRad << " arcmin at " << w.torque << " N·m, " << phase
          << "), more than max_slipped_points = " << o.max_slipped_points
          << ": the brake did not hold at " << out.torques.hold_nm
          << " N·m; raise hold_torque_nm or lower t_max_nm";
        throw std::runtime_error(m.str());
      }
      if (std::abs(w.twist - start.twist) > max_twist) {
        std::ostringstream m;
        m.precision(4);
        m << "torsional: the measured torque is " << w.torque << " N·m after "
          << (w.twist - start.twist) * kArcminPerRad << " arcmin of twist (" << phase
          << "), expected it to reach " << (dir > 0 ? "+" : "-") << t_max
          << " N·m within max_twist_rad = " << max_twist
          << " rad: is the output held and the torque sensor connected?";
        throw std::runtime_error(m.str());
      }
      if (progress) {
        progress(phase, progress_from + (progress_to - progress_from) *
                                            std::clamp(fraction(w.torque), 0.0, 1.0));
      }
      if (!p.loop.voided && done(w.torque)) return;
    }
  };
  branch(
      LoopBranch::kFirstLoading, +1, "torsional: first loading to +T_max", 0.0, 0.25,
      [&](double t) { return t >= t_max; }, [&](double t) { return t / t_max; });
  branch(
      LoopBranch::kUnloading, -1, "torsional: unloading to -T_max", 0.25, 0.75,
      [&](double t) { return t <= -t_max; }, [&](double t) { return (t_max - t) / (2 * t_max); });
  branch(
      LoopBranch::kReloading, +1, "torsional: reloading to zero", 0.75, 0.97,
      [&](double t) { return t >= -zero_band; }, [&](double t) { return (t + t_max) / t_max; });
  // The loop ends at zero torque: the brake lets go of an unloaded gear.
  bench.set_brake_torque(0);

  if (progress) progress("torsional analysis", 0.98);
  metrology::LoopSensors sensors;
  sensors.ratio = sense.ratio;
  sensors.output_encoder_step_rad = d.output_encoder_resolution_rad;
  sensors.input_encoder_step_rad = d.input_encoder_resolution_rad;
  sensors.torque_step_nm = d.torque_resolution_nm;
  for (const auto& term : d.twin_gear.te_terms) {
    if (term.order_input != 0)
      sensors.input_terms.push_back({term.amplitude_rad, term.order_input});
  }
  metrology::TorsionalLoopOptions analysis;
  analysis.rated_torque_nm = reference;
  analysis.lost_motion_fraction = o.lost_motion_fraction;
  analysis.zero_band_nm = zero_band;
  std::vector<metrology::LoopPoint> loop;
  for (const auto& p : out.points) loop.push_back(p.loop);
  out.result = metrology::analyse_torsional_loop(loop, sensors, analysis);
  if (progress) progress("torsional done", 1.0);
  return out;
}

}  // namespace wavebench::procedures
