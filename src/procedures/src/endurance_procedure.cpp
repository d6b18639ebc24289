#include "wavebench/procedures/endurance_procedure.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <future>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "wavebench/metrology/dynamic_te_input.hpp"
#include "wavebench/metrology/gear_sense.hpp"
#include "wavebench/procedures/dynamic_te_procedure.hpp"
#include "wavebench/procedures/sample_recorder.hpp"

namespace wavebench::procedures {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

void declare(OptionReader& r, EnduranceOptions& o) {
  r.number("input_rpm", o.input_rpm, 0, 1e5, false, {"rpm", "constant input speed"});
  r.number("run_in_s", o.run_in_s, 0, 3600, true,
           {"s", "at speed and load before recording (speed and temperature settle)"});
  r.integer("output_revolutions", o.output_revolutions, 1, 100000,
            {"",
             "output revolutions recorded, each analysed on its own (60 = 1 h at 100 rpm, "
             "N = 100)"});
  r.number("load_nm", o.load_nm, 0, 1e4, true, {"N·m", "brake torque during the run"});
  r.integer("mesh_harmonics", o.mesh_harmonics, 1, 10,
            {"", "mesh lines tracked per revolution: output orders z_F, 2·z_F, ..."});
}

// The recorded samples cut into output revolutions on the bench thread: each closed revolution
// waits in `closed` for the procedure (the same thread) to hand it to a worker. Only the
// revolution being recorded and those handed on but not yet analysed are in memory.
class RevolutionSplitter final : public bench::SampleObserver {
 public:
  explicit RevolutionSplitter(const model::GearSense& sense) : sense_(sense) {}
  void start() { recording_ = true; }
  void stop() { recording_ = false; }
  void on_sample(const storage::SyncSample& s) noexcept override {
    if (!recording_) return;
    try {
      current_.push_back(s);
      ++recorded_;
      if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid)) return;
      const double angle = sense_.model_output_angle(s.theta_out_rad);
      if (!started_) {
        start_angle_ = angle;
        started_ = true;
      } else if (std::abs(angle - start_angle_) >= kTwoPi) {
        closed_.push_back(std::move(current_));
        current_.clear();
        current_.push_back(s);  // the closing sample opens the next revolution
        start_angle_ = angle;
      }
    } catch (...) {
      recording_ = false;  // out of memory: the revolutions so far stand; run() sees the stop
      failed_ = true;
    }
  }
  std::deque<std::vector<storage::SyncSample>>& closed() { return closed_; }
  std::size_t recorded() const { return recorded_; }
  bool failed() const { return failed_; }

 private:
  model::GearSense sense_;
  bool recording_ = false, started_ = false, failed_ = false;
  double start_angle_ = 0;
  std::vector<storage::SyncSample> current_;
  std::deque<std::vector<storage::SyncSample>> closed_;
  std::size_t recorded_ = 0;
};

nlohmann::json optional_number(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

}  // namespace

std::vector<OptionSpec> EnduranceOptions::schema() {
  EnduranceOptions o;
  OptionReader r("endurance");
  declare(r, o);
  return r.described();
}

EnduranceOptions EnduranceOptions::from_json(const nlohmann::json& options) {
  EnduranceOptions o;
  OptionReader r(options, "endurance", schema());
  declare(r, o);
  return o;
}

nlohmann::json EnduranceOptions::to_json() const {
  return {{"input_rpm", input_rpm},
          {"run_in_s", run_in_s},
          {"output_revolutions", output_revolutions},
          {"load_nm", load_nm},
          {"mesh_harmonics", mesh_harmonics}};
}

RevolutionTrend analyse_revolution(std::vector<storage::SyncSample> samples,
                                   const bench::BenchDescription& bench,
                                   const metrology::GearTeeth& teeth, int mesh_harmonics) {
  RevolutionTrend t;
  try {
    const auto input = metrology::dynamic_te_input(samples);
    samples.clear();
    samples.shrink_to_fit();
    t.samples = input.time_s.size();
    t.first_receive_time_ns = input.first_receive_time_ns;
    t.last_receive_time_ns = input.last_receive_time_ns;
    metrology::DynamicTeOptions o;
    o.harmonics = mesh_harmonics;
    o.input_resolution_rad = bench.input_encoder_resolution_rad;
    o.output_resolution_rad = bench.output_encoder_resolution_rad;
    analysis::SpectrumAnalyser analyser;
    const auto predicted = predicted_components(bench.twin_gear, teeth);
    const auto r =
        metrology::analyse_dynamic_te(input.time_s, input.theta_in_rad, input.theta_out_rad,
                                       bench.sense, teeth, predicted, o, analyser);
    t.mean_arcsec = r.mean_arcsec;
    t.p2p_arcsec = r.p2p_arcsec;
    t.rms_arcsec = r.rms_arcsec;
    t.input_speed_hz = r.input_speed_hz;
    for (int k = 1; k <= mesh_harmonics; ++k) {
      const double order = static_cast<double>(k) * teeth.z_flex;
      double amplitude = 0, distance = INFINITY;
      for (std::size_t i = 0; i < r.order_output.size(); ++i) {
        if (std::abs(r.order_output[i] - order) < distance) {
          distance = std::abs(r.order_output[i] - order);
          amplitude = r.order_amplitude_arcsec[i];
        }
      }
      t.mesh_arcsec.push_back(distance <= 0.5 ? amplitude : 0.0);
    }
  } catch (const std::exception& e) {
    t.error = e.what();
  }
  return t;
}

nlohmann::json EnduranceOutcome::to_json() const {
  nlohmann::json rows = nlohmann::json::array();
  std::optional<double> first_temperature, last_temperature;
  double p2p_max = 0;
  const RevolutionTrend* first = nullptr;
  const RevolutionTrend* last = nullptr;
  for (const auto& r : revolutions) {
    nlohmann::json row = {{"revolution", r.revolution},
                          {"t_start_s", r.t_start_s},
                          {"t_end_s", r.t_end_s},
                          {"first_receive_time_ns", r.first_receive_time_ns},
                          {"last_receive_time_ns", r.last_receive_time_ns},
                          {"samples", r.samples},
                          {"mean_arcsec", r.mean_arcsec},
                          {"p2p_arcsec", r.p2p_arcsec},
                          {"rms_arcsec", r.rms_arcsec},
                          {"input_speed_hz", r.input_speed_hz},
                          {"mesh_arcsec", r.mesh_arcsec},
                          {"brake_temperature_c", optional_number(r.brake_temperature_c)}};
    if (!r.error.empty()) row["error"] = r.error;
    rows.push_back(std::move(row));
    if (r.brake_temperature_c) {
      if (!first_temperature) first_temperature = r.brake_temperature_c;
      last_temperature = r.brake_temperature_c;
    }
    if (!r.error.empty()) continue;
    if (!first) first = &r;
    last = &r;
    p2p_max = std::max(p2p_max, r.p2p_arcsec);
  }
  nlohmann::json summary = {
      {"revolutions_analysed",
       std::count_if(revolutions.begin(), revolutions.end(),
                     [](const RevolutionTrend& r) { return r.error.empty(); })},
      {"p2p_first_arcsec", first ? nlohmann::json(first->p2p_arcsec) : nlohmann::json()},
      {"p2p_last_arcsec", last ? nlohmann::json(last->p2p_arcsec) : nlohmann::json()},
      {"p2p_max_arcsec", first ? nlohmann::json(p2p_max) : nlohmann::json()},
      {"mean_drift_arcsec",
       first ? nlohmann::json(last->mean_arcsec - first->mean_arcsec) : nlohmann::json()},
      {"brake_temperature_rise_c", first_temperature
                                       ? nlohmann::json(*last_temperature - *first_temperature)
                                       : nlohmann::json()}};
  return {
      {"samples", samples},
      {"teeth",
       {{"z_flex", teeth.z_flex}, {"z_circ", teeth.z_circ}, {"wave_number", teeth.wave_number}}},
      {"mesh_orders", mesh_orders},
      {"summary", summary},
      {"revolutions", rows}};
}

EnduranceProcedure::EnduranceProcedure(EnduranceOptions options) : options_(std::move(options)) {}

RunPlan EnduranceProcedure::plan(const bench::BenchDescription& bench) const {
  const auto& o = options_;
  bench.sense.validate();
  RunPlan plan;
  if (o.load_nm > 0) plan.brake_torques_nm.push_back({"endurance.load_nm", o.load_nm, "N*m"});
  plan.input_speeds_rad_s.push_back({"endurance.input_rpm", o.input_rpm, "rpm", kTwoPi / 60});
  const double omega_in = o.input_rpm * kTwoPi / 60;
  // As run(): each revolution closes on the first sample past the whole turn.
  const double record_s = o.output_revolutions * 1.001 * kTwoPi * bench.sense.ratio / omega_in;
  plan.bench_time_s = planned_ramp_s(omega_in) + o.run_in_s + record_s + planned_ramp_s(omega_in);
  std::ostringstream terms;
  terms << "endurance.run_in_s " << o.run_in_s << " s + endurance.output_revolutions "
        << o.output_revolutions << " at endurance.input_rpm " << o.input_rpm << " (" << record_s
        << " s at ratio " << bench.sense.ratio << ")";
  plan.duration_terms = terms.str();
  return plan;
}

EnduranceOutcome EnduranceProcedure::run(bench::Bench& bench,
                                         const ProcedureProgress& progress) const {
  const auto& o = options_;
  const auto& d = bench.description();
  d.sense.validate();
  const double omega_in = o.input_rpm * kTwoPi / 60;
  const double output_rev_s = kTwoPi * d.sense.ratio / omega_in;

  EnduranceOutcome out;
  out.teeth = gear_teeth(d.twin_gear, d.sense.ratio);
  for (int k = 1; k <= o.mesh_harmonics; ++k) out.mesh_orders.push_back(k * out.teeth.z_flex);

  RevolutionSplitter splitter(d.sense);
  ObserverRegistration registration(bench, splitter);
  if (progress) progress("endurance run-in", 0);
  bench.set_brake_torque(o.load_nm);
  bench.run_input_velocity(omega_in);
  bench.wait_for(o.run_in_s);

  // Workers analyse closed revolutions while the bench goes on; each result is collected in
  // order. Never more than kMaxPendingRevolutions wait: on the simulated clock the bench may
  // outrun the analysis, and then it waits (no bench time passes meanwhile).
  std::deque<std::future<RevolutionTrend>> pending;
  std::deque<std::optional<double>> pending_temperature;
  std::int64_t record_start_ns = 0;
  bool have_start = false;
  int handed = 0;
  const auto collect_oldest = [&] {
    auto r = pending.front().get();
    pending.pop_front();
    r.revolution = static_cast<int>(out.revolutions.size()) + 1;
    r.brake_temperature_c = pending_temperature.front();
    pending_temperature.pop_front();
    r.t_start_s = 1e-9 * static_cast<double>(r.first_receive_time_ns - record_start_ns);
    r.t_end_s = 1e-9 * static_cast<double>(r.last_receive_time_ns - record_start_ns);
    out.revolutions.push_back(std::move(r));
  };
  const auto hand_on_closed = [&] {
    auto& closed = splitter.closed();
    while (!closed.empty() && handed < o.output_revolutions) {
      auto samples = std::move(closed.front());
      closed.pop_front();
      if (!have_start && !samples.empty()) {
        record_start_ns = samples.front().receive_time_ns;
        have_start = true;
      }
      pending_temperature.push_back(bench.acquisition_stats().brake_coil_temperature_c);
      pending.push_back(std::async(std::launch::async, analyse_revolution, std::move(samples),
                                   std::cref(d), out.teeth, o.mesh_harmonics));
      ++handed;
      while (pending.size() > kMaxPendingRevolutions) collect_oldest();
    }
    closed.clear();  // beyond the revolutions asked for
  };

  splitter.start();
  const double expected_s = o.output_revolutions * output_rev_s;
  double last_report = 0;
  const bool done = bench.wait_until(
      [&] {
        hand_on_closed();
        const double fraction = static_cast<double>(handed) / o.output_revolutions;
        if (progress && fraction - last_report >= 0.01) {
          last_report = fraction;
          progress("endurance revolution " + std::to_string(handed) + "/" +
                       std::to_string(o.output_revolutions),
                   0.02 + 0.96 * fraction);
        }
        return handed >= o.output_revolutions || splitter.failed();
      },
      1.5 * expected_s + 10);
  splitter.stop();
  bench.stop_motion();
  bench.set_brake_torque(0);
  while (!pending.empty()) collect_oldest();
  out.samples = splitter.recorded();
  if (splitter.failed()) {
    throw std::runtime_error("endurance: out of memory after " + std::to_string(handed) +
                             " revolutions");
  }
  if (!done) {
    throw std::runtime_error("endurance: the output did not turn " +
                             std::to_string(o.output_revolutions) + " revolutions in " +
                             std::to_string(1.5 * expected_s + 10) + " s of bench time");
  }
  if (progress) progress("endurance done", 1.0);
  return out;
}

}  // namespace wavebench::procedures
