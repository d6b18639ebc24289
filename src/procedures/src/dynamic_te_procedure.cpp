#include "wavebench/procedures/dynamic_te_procedure.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>

#include "wavebench/metrology/dynamic_te_record.hpp"
#include "wavebench/metrology/gear_sense.hpp"
#include "wavebench/procedures/option_reader.hpp"
#include "wavebench/procedures/sample_recorder.hpp"

namespace wavebench::procedures {

namespace {
constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr std::size_t kTracePoints = 4000;
// The order spectra shown: up to a little beyond the highest named harmonic of the mesh.
constexpr double kMaxOrderShown = 3.5;  // TE trace kept in results.json for plots
// The order spectrum's grid at most (8 MiB, 17 output revolutions at 60,000 samples each):
// its transform holds the grid and FFTW's own tables of the same size, so a longer grid would
// make a run's memory grow with its length. A longer run's order spectrum is over its first
// whole revolutions (order_spectrum.revolutions says how many); the Welch spectrum, the
// figures and the trace are over all of them.
constexpr std::size_t kMaxOrderGridPoints = std::size_t{1} << 20;

// Feeds the record from the acquisition thread while recording.
class DynamicTeRecorder final : public bench::SampleObserver {
 public:
  explicit DynamicTeRecorder(metrology::DynamicTeRecord& record) : record_(record) {}
  void start() { recording_.store(true, std::memory_order_release); }
  void stop() { recording_.store(false, std::memory_order_release); }
  void on_sample(const storage::SyncSample& sample) noexcept override {
    if (recording_.load(std::memory_order_acquire)) record_.add(sample);
  }

 private:
  metrology::DynamicTeRecord& record_;
  std::atomic<bool> recording_{false};
};
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

metrology::GearTeeth gear_teeth(const model::GearParams& twin, double ratio) {
  metrology::GearTeeth t;
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

std::vector<metrology::PredictedComponent> predicted_components(
    const model::GearParams& twin, const metrology::GearTeeth& teeth) {
  std::vector<metrology::PredictedComponent> out;
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
  nlohmann::json j = metrology::to_json(result);
  j["samples"] = samples;
  j["skipped_invalid"] = skipped_invalid;
  j["skipped_out_of_order"] = skipped_out_of_order;
  j["skipped_not_advancing"] = skipped_not_advancing;
  j["missed_cycles"] = missed_cycles;
  j["record"] = {{"first_receive_time_ns", first_receive_time_ns},
                 {"last_receive_time_ns", last_receive_time_ns}};
  j["teeth"] = {
      {"z_flex", teeth.z_flex}, {"z_circ", teeth.z_circ}, {"wave_number", teeth.wave_number}};
  // The record's own trace: at most two points (min and max) per block of samples.
  const std::size_t n = result.te_arcsec.size();
  const std::size_t stride = 1;
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
  const double max_order = kMaxOrderShown * std::max(teeth.z_flex, 1);
  for (std::size_t i = 0; i < result.order_output.size() && result.order_output[i] <= max_order;
       ++i) {
    orders.push_back(result.order_output[i]);
    amps.push_back(result.order_amplitude_arcsec[i]);
  }
  j["order_spectrum"] = {{"order_output", orders},
                         {"amplitude_arcsec", amps},
                         {"revolutions", result.order_revolutions}};
  j["order_spectrum_averaged"] = {{"order_output", result.averaged_order_output},
                                  {"amplitude_arcsec", result.averaged_amplitude_arcsec},
                                  {"revolutions", result.averaged_revolutions},
                                  {"revolutions_dropped", result.averaged_revolutions_dropped}};
  j["trace"]["samples_per_block"] = result.trace_stride;
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

  // The record is reduced as it is acquired (procedures/dynamic_te_record.hpp): its grid is
  // the only thing that grows with the run, one double per sample.
  const double expected_samples = o.output_revolutions * 1.005 * output_rev_s / d.sync_period_s;
  metrology::DynamicTeRecordShape shape;
  shape.output_direction = d.sense.direction_sign;  // the input turns forward
  shape.points_per_revolution = metrology::smooth_size_at_least(
      static_cast<std::size_t>(std::ceil(output_rev_s / d.sync_period_s)));
  shape.max_revolutions = std::clamp<std::size_t>(
      static_cast<std::size_t>(std::floor(span / kTwoPi)), 1,
      std::max<std::size_t>(1, kMaxOrderGridPoints / shape.points_per_revolution));
  shape.trace_stride = std::max<std::size_t>(
      1, static_cast<std::size_t>(expected_samples / static_cast<double>(kTracePoints)));
  shape.trace_capacity = 2 * (kTracePoints + 16);
  shape.welch = metrology::RevolutionWelch::Transform::kOnWorker;  // add() is on acquisition
  metrology::DynamicTeRecord record(d.sense, shape);
  DynamicTeRecorder recorder(record);
  std::optional<ObserverRegistration> registration;
  registration.emplace(bench, recorder);
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
  registration.reset();
  bench.stop_motion();
  bench.set_brake_torque(0);
  if (!done) {
    throw std::runtime_error("dynamic TE: the output did not turn " +
                             std::to_string(o.output_revolutions) + " revolutions in " +
                             std::to_string(1.5 * expected_s + 10) + " s of bench time");
  }

  if (progress) progress("dynamic analysis", 0.95);
  DynamicTeOutcome out;
  const auto& counts = record.counts();
  out.samples = record.samples_offered();
  out.skipped_invalid = counts.skipped_invalid;
  out.skipped_out_of_order = counts.skipped_out_of_order;
  out.skipped_not_advancing = counts.skipped_not_advancing;
  out.missed_cycles = counts.missed_cycles;
  out.first_receive_time_ns = counts.first_receive_time_ns;
  out.last_receive_time_ns = counts.last_receive_time_ns;
  out.teeth = gear_teeth(d.twin_gear, d.sense.ratio);
  const auto predicted = predicted_components(d.twin_gear, out.teeth);
  metrology::DynamicTeOptions analysis;
  analysis.max_peaks = o.max_peaks;
  analysis.harmonics = o.harmonics;
  analysis.input_resolution_rad = d.input_encoder_resolution_rad;
  analysis.output_resolution_rad = d.output_encoder_resolution_rad;
  analysis.max_order_kept = kMaxOrderShown * std::max(out.teeth.z_flex, 1);
  out.result = record.finish(out.teeth, predicted, analysis);
  if (progress) progress("dynamic done", 1.0);
  return out;
}

}  // namespace wavebench::procedures
