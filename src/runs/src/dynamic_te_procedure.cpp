#include "wavebench/runs/dynamic_te_procedure.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "wavebench/procedures/gear_sense.hpp"
#include "wavebench/runs/option_reader.hpp"
#include "wavebench/runs/sample_recorder.hpp"

namespace wavebench::runs {

namespace {
constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr std::size_t kTracePoints = 4000;  // TE trace kept in results.json for plots
}  // namespace

namespace {

// The one declaration of the options: parses them, and describes them for the schema.
void declare(OptionReader& r, DynamicTeOptions& o) {
  r.number("input_rpm", o.input_rpm, 0, 1e5, false, {"rpm", "constant input speed"});
  r.number("run_in_s", o.run_in_s, 0, 3600, true,
           {"s", "at speed before recording (speed and temperature settle)"});
  r.number("output_revolutions", o.output_revolutions, 1, 1000, true,
           {"", "output revolutions recorded for the TE trace and its order spectrum"});
  r.number("load_nm", o.load_nm, 0, 1e4, true, {"N·m", "brake torque during the run"});
  r.integer("max_peaks", o.max_peaks, 1, 200, {"", "largest peaks of the order spectrum reported"});
  r.integer("harmonics", o.harmonics, 1, 20,
            {"", "harmonics of the output 1/rev and of the mesh named in the spectrum"});
}

}  // namespace

std::vector<OptionSpec> DynamicTeOptions::schema() {
  DynamicTeOptions o;
  OptionReader r("dynamic");
  declare(r, o);
  return r.described();
}

DynamicTeOptions DynamicTeOptions::from_json(const nlohmann::json& options) {
  DynamicTeOptions o;
  OptionReader r(options, "dynamic", schema());
  declare(r, o);
  return o;
}

nlohmann::json DynamicTeOptions::to_json() const {
  return {{"input_rpm", input_rpm},
          {"run_in_s", run_in_s},
          {"output_revolutions", output_revolutions},
          {"load_nm", load_nm},
          {"max_peaks", max_peaks},
          {"harmonics", harmonics}};
}

procedures::GearTeeth gear_teeth(const model::GearParams& twin, double ratio) {
  procedures::GearTeeth t;
  t.wave_number = twin.geometry.wave_number > 0 ? twin.geometry.wave_number : 2;
  if (twin.geometry.z_flex > 0 && twin.geometry.z_circ > 0) {
    t.z_flex = twin.geometry.z_flex;
    t.z_circ = twin.geometry.z_circ;
  } else {
    t.z_flex = static_cast<int>(std::lround(t.wave_number * ratio));
    t.z_circ = t.z_flex + t.wave_number;
  }
  return t;
}

std::vector<procedures::PredictedComponent> predicted_components(
    const model::GearParams& twin, const procedures::GearTeeth& teeth) {
  std::vector<procedures::PredictedComponent> out;
  const double mesh_order = static_cast<double>(teeth.wave_number) * teeth.z_circ;
  bool has_mesh = false;
  for (const auto& t : twin.te_terms) {
    if (t.order_input == 0 && t.order_output == 0) continue;  // an offset has no line
    out.push_back({t.source, t.order_input, t.order_output, t.amplitude_rad});
    has_mesh = has_mesh || (t.order_input == mesh_order && t.order_output == 0);
  }
  if (!has_mesh && teeth.z_circ > 0) {
    out.push_back({"tooth mesh (U·z_C per wave-generator revolution)", mesh_order, 0, 0});
  }
  return out;
}

nlohmann::json DynamicTeOutcome::to_json() const {
  nlohmann::json j = procedures::to_json(result);
  j["samples"] = samples;
  j["skipped_invalid"] = skipped_invalid;
  j["skipped_out_of_order"] = skipped_out_of_order;
  j["skipped_not_advancing"] = skipped_not_advancing;
  j["missed_cycles"] = missed_cycles;
  j["record"] = {{"first_receive_time_ns", first_receive_time_ns},
                 {"last_receive_time_ns", last_receive_time_ns}};
  j["teeth"] = {
      {"z_flex", teeth.z_flex}, {"z_circ", teeth.z_circ}, {"wave_number", teeth.wave_number}};
  const std::size_t n = result.te_arcsec.size();
  const std::size_t stride = std::max<std::size_t>(1, n / kTracePoints);
  nlohmann::json t = nlohmann::json::array(), a = nlohmann::json::array(),
                 te = nlohmann::json::array();
  for (std::size_t i = 0; i < n; i += stride) {
    t.push_back(result.time_s[i]);
    // From the start of the record: the encoder's multi-turn zero is arbitrary.
    a.push_back((result.output_angle_rad[i] - result.output_angle_rad[0]) * 180 / std::numbers::pi);
    te.push_back(result.te_arcsec[i]);
  }
  j["trace"] = {{"time_s", t}, {"output_angle_deg", a}, {"te_arcsec", te}};
  // The order spectrum up to a little beyond the highest named harmonic of the mesh.
  nlohmann::json orders = nlohmann::json::array(), amps = nlohmann::json::array();
  const double max_order = 3.5 * std::max(teeth.z_flex, 1);
  for (std::size_t i = 0; i < result.order_output.size() && result.order_output[i] <= max_order;
       ++i) {
    orders.push_back(result.order_output[i]);
    amps.push_back(result.order_amplitude_arcsec[i]);
  }
  j["order_spectrum"] = {{"order_output", orders}, {"amplitude_arcsec", amps}};
  return j;
}

DynamicTeProcedure::DynamicTeProcedure(DynamicTeOptions options) : options_(std::move(options)) {}

RunPlan DynamicTeProcedure::plan(const bench::BenchDescription& bench) const {
  const auto& o = options_;
  bench.sense.validate();
  RunPlan plan;
  if (o.load_nm > 0) plan.brake_torques_nm.push_back({"dynamic.load_nm", o.load_nm, "N*m"});
  plan.input_speeds_rad_s.push_back({"dynamic.input_rpm", o.input_rpm, "rpm", kTwoPi / 60});
  // As run(): speed up, run in, record the revolutions (and the margin that closes them),
  // stop.
  const double omega_in = o.input_rpm * kTwoPi / 60;
  const double record_s = o.output_revolutions * 1.005 * kTwoPi * bench.sense.ratio / omega_in;
  plan.bench_time_s = planned_ramp_s(omega_in) + o.run_in_s + record_s + planned_ramp_s(omega_in);
  std::ostringstream terms;
  terms << "dynamic.run_in_s " << o.run_in_s << " s + dynamic.output_revolutions "
        << o.output_revolutions << " at dynamic.input_rpm " << o.input_rpm << " (" << record_s
        << " s at ratio " << bench.sense.ratio << ")";
  plan.duration_terms = terms.str();
  return plan;
}

DynamicTeOutcome DynamicTeProcedure::run(bench::Bench& bench,
                                         const ProcedureProgress& progress) const {
  const auto& o = options_;
  const auto& d = bench.description();
  d.sense.validate();
  const double omega_in = o.input_rpm * kTwoPi / 60;
  const double output_rev_s = kTwoPi * d.sense.ratio / omega_in;  // one output revolution
  // A little beyond the whole revolutions so that the analysis can close them exactly.
  const double span = o.output_revolutions * kTwoPi * 1.005;

  SampleRecorder recorder;
  ObserverRegistration registration(bench, recorder);
  if (progress) progress("dynamic run-in", 0);
  bench.set_brake_torque(o.load_nm);
  bench.run_input_velocity(omega_in);
  bench.wait_for(o.run_in_s);

  recorder.start();
  const double start = d.sense.model_output_angle(bench.latest_sample().theta_out_rad);
  const double expected_s = o.output_revolutions * output_rev_s;
  double last_report = 0;
  const bool done = bench.wait_until(
      [&] {
        const double turned =
            std::abs(d.sense.model_output_angle(bench.latest_sample().theta_out_rad) - start);
        const double fraction = std::min(1.0, turned / span);
        if (progress && fraction - last_report >= 0.01) {
          last_report = fraction;
          progress("dynamic recording", 0.05 + 0.9 * fraction);
        }
        return turned >= span;
      },
      1.5 * expected_s + 10);
  recorder.stop();
  bench.stop_motion();
  bench.set_brake_torque(0);
  if (!done) {
    throw std::runtime_error("dynamic TE: the output did not turn " +
                             std::to_string(o.output_revolutions) + " revolutions in " +
                             std::to_string(1.5 * expected_s + 10) + " s of bench time");
  }

  if (progress) progress("dynamic analysis", 0.95);
  DynamicTeOutcome out;
  const auto input = procedures::dynamic_te_input(recorder.samples());
  out.samples = recorder.samples().size();
  out.skipped_invalid = input.skipped_invalid;
  out.skipped_out_of_order = input.skipped_out_of_order;
  out.skipped_not_advancing = input.skipped_not_advancing;
  out.missed_cycles = input.missed_cycles;
  out.first_receive_time_ns = input.first_receive_time_ns;
  out.last_receive_time_ns = input.last_receive_time_ns;
  out.teeth = gear_teeth(d.twin_gear, d.sense.ratio);
  const auto predicted = predicted_components(d.twin_gear, out.teeth);
  procedures::DynamicTeOptions analysis;
  analysis.max_peaks = o.max_peaks;
  analysis.harmonics = o.harmonics;
  analysis.input_resolution_rad = d.input_encoder_resolution_rad;
  analysis.output_resolution_rad = d.output_encoder_resolution_rad;
  analysis::SpectrumAnalyser analyser;
  out.result = procedures::analyse_dynamic_te(input.time_s, input.theta_in_rad, input.theta_out_rad,
                                              d.sense, out.teeth, predicted, analysis, analyser);
  if (progress) progress("dynamic done", 1.0);
  return out;
}

}  // namespace wavebench::runs
