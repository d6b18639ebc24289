#include "wavebench/procedures/static_te_procedure.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "wavebench/metrology/figure_propagation.hpp"
#include "wavebench/procedures/option_reader.hpp"
#include "wavebench/procedures/sample_recorder.hpp"

namespace wavebench::procedures {

namespace {

using metrology::Direction;

std::string load_label(double load_nm) {
  std::ostringstream s;
  s << load_nm << " N·m";
  return s.str();
}

// Waits until the output has settled. The detector sees means over short blocks: a raw encoder
// sample's noise alone would exceed any useful speed or drift threshold.
bool wait_settled(bench::Bench& bench, const StaticTeOptions& o) {
  metrology::SettleDetector detector(o.settle);
  const double t0 = bench.now();
  detector.start(t0);
  double block_start = t0, sum = 0;
  int count = 0;
  bool have_previous = false;
  double previous_mean = 0, previous_time = 0;
  auto state = metrology::SettleState::kSettling;
  bench.wait_until(
      [&] {
        const auto& s = bench.latest_sample();
        const double t = bench.now();
        if (s.valid(storage::kThetaOutValid)) {
          sum += s.theta_out_rad;
          ++count;
        }
        if (t - block_start >= o.settle_block_s - 1e-12 && count > 0) {
          const double mean = sum / count;
          if (have_previous) {
            const double speed = (mean - previous_mean) / (t - previous_time);
            state = detector.add(t, mean, speed);
          }
          have_previous = true;
          previous_mean = mean;
          previous_time = t;
          block_start = t;
          sum = 0;
          count = 0;
        }
        return state != metrology::SettleState::kSettling;
      },
      o.settle.max_settle_s + 2 * o.settle_block_s);
  return state == metrology::SettleState::kSettled;
}

metrology::StaticTePoint average_window(bench::Bench& bench, SampleRecorder& recorder,
                                         double window_s, int position,
                                         const metrology::GearSense& sense) {
  recorder.start();
  bench.wait_for(window_s);
  recorder.stop();
  double th_in = 0, th_out = 0, torque = 0;
  int angles = 0, torques = 0;
  std::vector<double> te;  // per sample: its scatter is the noise the window mean keeps
  for (const auto& s : recorder.samples()) {
    if (s.valid(storage::kThetaInValid) && s.valid(storage::kThetaOutValid)) {
      th_in += s.theta_in_rad;
      th_out += s.theta_out_rad;
      te.push_back(sense.transmission_error(s.theta_in_rad, s.theta_out_rad));
      ++angles;
    }
    if (s.valid(storage::kTorqueValid)) {
      torque += s.torque_nm;
      ++torques;
    }
  }
  if (angles == 0) {
    throw std::runtime_error("static TE: no sample with both angles valid in the " +
                             std::to_string(window_s) + " s window at position " +
                             std::to_string(position));
  }
  metrology::StaticTePoint p;
  p.position = position;
  p.theta_in_rad = th_in / angles;
  p.theta_out_rad = th_out / angles;
  p.torque_nm = torques > 0 ? torque / torques : std::numeric_limits<double>::quiet_NaN();
  p.te_noise_rad = metrology::standard_of_window_mean(te);
  return p;
}

}  // namespace

namespace {

// The one declaration of the options: parses them, and describes them for the schema.
void declare(OptionReader& r, StaticTeOptions& o) {
  r.integer("positions", o.positions, 2, 3600,
            {"", "positions equally spaced over one output revolution"});
  r.numbers("loads_nm", o.loads_nm, 0, 1e4, true, 1,
            {"N·m", "brake torque of each pair of passes (forward, then reverse)"});
  r.number("window_s", o.window_s, 0, 600, false,
           {"s", "θ_in, θ_out and torque averaged over this at each settled position"});
  r.number("move_speed_rad_s", o.move_speed_rad_s, 0, 1e4, false,
           {"rad/s", "input profile velocity between positions"});
  r.number("run_up_steps", o.run_up_steps, 0, 1, false,
           {"", "run-up before a pass, in position steps (approach side)"});
  r.number("approach_rad", o.approach_rad, 0, 1e3, true,
           {"rad", "input angle of the slow final approach (no overshoot across the backlash)"});
  r.number("approach_speed_rad_s", o.approach_speed_rad_s, 0, 1e4, false,
           {"rad/s", "input speed of the slow final approach"});
  r.number("brake_settle_s", o.brake_settle_s, 0, 600, true,
           {"s", "wait after a new brake torque, before the run-up move"});
  r.number("settle_block_s", o.settle_block_s, 0, 10, false,
           {"s", "the settle detector sees means over blocks this long (encoder noise)"});
  r.number("settle_max_speed_rad_s", o.settle.max_speed_rad_s, 0, 1e3, false,
           {"rad/s", "settled: output speed under this ..."});
  r.number("settle_max_drift_rad", o.settle.max_drift_rad, 0, 1, false,
           {"rad", "... and output drift under this ..."});
  r.number("settle_window_s", o.settle.window_s, 0, 600, false, {"s", "... for this long"});
  r.number("max_settle_s", o.settle.max_settle_s, 0, 3600, false,
           {"s", "otherwise averaged anyway after this, and counted as a settle timeout"});
}

}  // namespace

std::vector<OptionSpec> StaticTeOptions::schema() {
  StaticTeOptions o;
  OptionReader r("static");
  declare(r, o);
  return r.described();
}

StaticTeOptions StaticTeOptions::from_json(const nlohmann::json& options) {
  StaticTeOptions o;
  OptionReader r(options, "static", schema());
  declare(r, o);
  o.settle.validate();
  return o;
}

nlohmann::json StaticTeOptions::to_json() const {
  return {{"positions", positions},
          {"loads_nm", loads_nm},
          {"window_s", window_s},
          {"move_speed_rad_s", move_speed_rad_s},
          {"run_up_steps", run_up_steps},
          {"approach_rad", approach_rad},
          {"approach_speed_rad_s", approach_speed_rad_s},
          {"brake_settle_s", brake_settle_s},
          {"settle_block_s", settle_block_s},
          {"settle_max_speed_rad_s", settle.max_speed_rad_s},
          {"settle_max_drift_rad", settle.max_drift_rad},
          {"settle_window_s", settle.window_s},
          {"max_settle_s", settle.max_settle_s}};
}

nlohmann::json StaticTeOutcome::to_json() const {
  nlohmann::json j = metrology::to_json(result);
  // Issue #5 fixes the keys of a `static` entry; the mean torque stays in every point.
  for (auto& entry : j["static"]) entry.erase("mean_torque_nm");
  j["settle_timeouts"] = settle_timeouts;
  return j;
}

StaticTeProcedure::StaticTeProcedure(StaticTeOptions options) : options_(std::move(options)) {}

RunPlan StaticTeProcedure::plan(const bench::BenchDescription& bench) const {
  const auto& o = options_;
  bench.sense.validate();
  RunPlan plan;
  for (std::size_t i = 0; i < o.loads_nm.size(); ++i) {
    plan.brake_torques_nm.push_back(
        {"static.loads_nm[" + std::to_string(i) + "]", o.loads_nm[i], "N*m"});
  }
  plan.input_speeds_rad_s.push_back({"static.move_speed_rad_s", o.move_speed_rad_s, "rad/s"});
  if (o.approach_rad > 0) {
    plan.input_speeds_rad_s.push_back(
        {"static.approach_speed_rad_s", o.approach_speed_rad_s, "rad/s"});
  }
  // As run(): per load the brake settles, then two passes of a run-up and, at each position,
  // a move to the approach point, the slow approach, the settle and the window. The settle is
  // taken as one settle window of quiet plus two blocks to see it; a timeout would be
  // max_settle_s.
  const double step = 2 * std::numbers::pi * bench.sense.ratio / o.positions;
  const double run_up = o.run_up_steps * step;
  double position_s = o.settle.window_s + 2 * o.settle_block_s + o.window_s;
  if (o.approach_rad > 0) {
    position_s += planned_move_s(step - o.approach_rad, o.move_speed_rad_s) +
                  planned_move_s(o.approach_rad, o.approach_speed_rad_s);
  } else {
    position_s += planned_move_s(step, o.move_speed_rad_s);
  }
  const double pass_s = planned_move_s(run_up, o.move_speed_rad_s) + o.positions * position_s;
  const auto loads = static_cast<double>(o.loads_nm.size());
  plan.bench_time_s = loads * (o.brake_settle_s + 2 * pass_s);
  std::ostringstream terms;
  terms << "static.positions " << o.positions << " x " << o.loads_nm.size()
        << " static.loads_nm x 2 directions x " << position_s
        << " s (moves at static.move_speed_rad_s and static.approach_speed_rad_s, settle, "
           "static.window_s)";
  plan.duration_terms = terms.str();
  return plan;
}

StaticTeOutcome StaticTeProcedure::run(bench::Bench& bench,
                                       const ProcedureProgress& progress) const {
  const auto& o = options_;
  const auto& sense = bench.description().sense;
  sense.validate();
  // One output revolution is N input revolutions; the sign of the output does not matter here
  // because TE is taken in the model's convention (GearSense).
  const double step = 2 * std::numbers::pi * sense.ratio / o.positions;
  const double origin = bench.latest_sample().theta_in_rad;
  const int total = static_cast<int>(o.loads_nm.size()) * 2 * o.positions;
  int done = 0;

  metrology::StaticTeUncertaintyInputs uncertainty;
  uncertainty.input_resolution_rad = bench.description().input_encoder_resolution_rad;
  uncertainty.output_resolution_rad = bench.description().output_encoder_resolution_rad;
  uncertainty.settle_drift_rad = o.settle.max_drift_rad;

  SampleRecorder recorder;
  ObserverRegistration registration(bench, recorder);
  StaticTeOutcome out;
  for (double load : o.loads_nm) {
    bench.set_brake_torque(load);
    bench.wait_for(o.brake_settle_s);
    for (Direction d : {Direction::kForward, Direction::kReverse}) {
      const bool forward = d == Direction::kForward;
      const std::string phase =
          std::string("static ") + metrology::direction_name(d) + " " + load_label(load);
      metrology::StaticTePass pass;
      pass.direction = d;
      pass.load_nm = load;
      // The run-up makes the first position of the pass approached from the pass's side.
      const double run_up = o.run_up_steps * step;
      bench.move_input_to(forward ? origin - run_up : origin + (o.positions - 1) * step + run_up,
                          o.move_speed_rad_s);
      for (int i = 0; i < o.positions; ++i) {
        const int k = forward ? i : o.positions - 1 - i;
        if (progress) progress(phase, static_cast<double>(done) / total);
        const double target = origin + k * step;
        if (o.approach_rad > 0) {
          bench.move_input_to(forward ? target - o.approach_rad : target + o.approach_rad,
                              o.move_speed_rad_s);
        }
        bench.move_input_to(target,
                            o.approach_rad > 0 ? o.approach_speed_rad_s : o.move_speed_rad_s);
        if (!wait_settled(bench, o)) ++out.settle_timeouts;
        pass.points.push_back(average_window(bench, recorder, o.window_s, k, sense));
        if (point_sink_) {
          const auto r = metrology::static_point_result(pass.points.back(), sense, uncertainty);
          point_sink_({r.output_angle_deg, r.te_arcmin * 60.0, load, r.torque_nm,
                       metrology::direction_name(d)});
        }
        ++done;
      }
      out.passes.push_back(std::move(pass));
      if (finished_sink_) {
        // A copy of the passes so far; their analysis waits until it is asked for.
        finished_sink_({[passes = out.passes, timeouts = out.settle_timeouts, sense, uncertainty] {
                          StaticTeOutcome so_far;
                          so_far.passes = passes;
                          so_far.settle_timeouts = timeouts;
                          so_far.result = metrology::analyse_static_te(passes, sense, uncertainty);
                          return so_far.to_json();
                        },
                        static_cast<int>(out.passes.size()),
                        static_cast<int>(o.loads_nm.size()) * 2, "passes"});
      }
    }
  }
  bench.set_brake_torque(0);
  if (progress) progress("static analysis", 1.0);
  out.result = metrology::analyse_static_te(out.passes, sense, uncertainty);
  return out;
}

}  // namespace wavebench::procedures
