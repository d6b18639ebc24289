#include "synthetic_run.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "wavebench/storage/sample_log.hpp"

namespace wavebench::benchmarks {
namespace {

namespace fs = std::filesystem;
constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kArcsecPerRad = 180.0 * 3600.0 / std::numbers::pi;

// A small deterministic generator (the bytes must not depend on the library's engines).
struct Lcg {
  std::uint64_t state = 0x2545F4914F6CDD1DULL;
  double uniform() {  // [-1, 1)
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 4503599627370496.0 - 1.0;
  }
};

nlohmann::json built_in_results(const SyntheticRunSpec& spec) {
  const double f_in = spec.input_rpm / 60.0, f_out = f_in / spec.ratio;
  nlohmann::json peaks = nlohmann::json::array();
  const auto line = [&](const char* name, double order, double amplitude) {
    peaks.push_back({{"name", name},
                     {"order_output", order},
                     {"frequency_hz", order * f_out},
                     {"amplitude_arcsec", amplitude}});
  };
  line("1/rev output", 1, spec.te_1_arcsec);
  line("2/rev output", 2, spec.te_2_arcsec);
  line("mesh 2N", 2 * spec.ratio, spec.te_mesh_arcsec);
  const double rms =
      std::sqrt(0.5 * (spec.te_1_arcsec * spec.te_1_arcsec + spec.te_2_arcsec * spec.te_2_arcsec +
                       spec.te_mesh_arcsec * spec.te_mesh_arcsec));
  return {{"procedure", "dynamic"},
          {"gear", {{"ratio", spec.ratio}, {"direction_sign", 1}}},
          {"dynamic",
           {{"samples", spec.samples},
            {"input_speed_hz", f_in},
            {"rms_arcsec", rms},
            {"p2p_arcsec", 2 * (spec.te_1_arcsec + spec.te_2_arcsec + spec.te_mesh_arcsec)},
            {"peaks", peaks}}},
          {"acquisition", {{"sync_rate_hz", spec.rate_hz}}}};
}

// θ_in at time t: a ramp up over ramp_s, steady, a ramp down over the last ramp_s.
double input_angle(const SyntheticRunSpec& spec, double t, double duration) {
  const double w = kTwoPi * spec.input_rpm / 60.0, r = spec.ramp_s;
  const double up = std::min(t, r);
  double angle = 0.5 * w / r * up * up;  // ramp up
  if (t > r) angle += w * (std::min(t, duration - r) - r);
  if (t > duration - r) {
    const double d = t - (duration - r);
    angle += w * d - 0.5 * w / r * d * d;  // ramp down
  }
  return angle;
}

}  // namespace

double synthetic_te_arcsec(const SyntheticRunSpec& spec, double theta_out_rad) {
  return spec.te_1_arcsec * std::sin(theta_out_rad) +
         spec.te_2_arcsec * std::sin(2 * theta_out_rad + 0.4) +
         spec.te_mesh_arcsec * std::sin(2 * spec.ratio * theta_out_rad + 1.1);
}

void write_synthetic_run_files(const fs::path& dir, const SyntheticRunSpec& spec) {
  fs::create_directories(dir);
  const double duration = static_cast<double>(spec.samples) / spec.rate_hz;
  const double period_ns = 1e9 / spec.rate_hz;
  storage::SampleLogWriterOptions options;
  options.flush_every_records = 4096;
  options.checkpoint_every_records = 0;  // a tool: one fdatasync at the end
  storage::SampleLogWriter log(dir / "samples.wbs", options);
  std::FILE* twin = nullptr;
  if (spec.twin_csv) {
    twin = std::fopen((dir / "twin.csv").c_str(), "w");
    if (!twin) throw std::runtime_error("cannot write " + (dir / "twin.csv").string());
    std::fputs("t,index,measured_te_arcsec,predicted_te_arcsec,residual_arcsec\n", twin);
  }
  Lcg noise;
  std::uint32_t counter = 1;
  const std::int64_t t0_ns = 1'790'000'000'000'000'000;
  for (std::size_t i = 0; i < spec.samples; ++i) {
    if (i > 0 && i % 100'000 == 0) counter = counter % 240 + 1;  // a missed SYNC
    const double t = static_cast<double>(i) / spec.rate_hz;
    const double th_in = input_angle(spec, t, duration);
    const double ideal_out = th_in / spec.ratio;
    const double te = synthetic_te_arcsec(spec, ideal_out) + spec.noise_arcsec * noise.uniform();
    storage::SyncSample s;
    s.sync_counter = counter;
    counter = counter % 240 + 1;
    s.flags = storage::kAllChannelsValid;
    s.receive_time_ns = t0_ns + static_cast<std::int64_t>(static_cast<double>(i) * period_ns +
                                                          20'000 * noise.uniform());
    s.theta_in_rad = th_in;
    s.theta_out_rad = ideal_out + te / kArcsecPerRad;
    s.input_speed_rad_s = kTwoPi * spec.input_rpm / 60.0;
    s.torque_nm = 20 + 0.5 * std::sin(ideal_out);
    s.brake_current_a = 0.8;
    s.brake_torque_nm = 20;
    log.append(s);
    if (twin) {
      const double predicted = 0.97 * synthetic_te_arcsec(spec, ideal_out);
      std::fprintf(twin, "%.6f,%zu,%.4f,%.4f,%.4f\n", t, i, te, predicted, te - predicted);
    }
  }
  log.close();
  if (twin && std::fclose(twin) != 0) {
    throw std::runtime_error("cannot write " + (dir / "twin.csv").string());
  }
  nlohmann::json results =
      spec.results_template.is_object() ? spec.results_template : built_in_results(spec);
  results["dynamic"]["samples"] = spec.samples;
  results["gear"]["ratio"] = spec.ratio;
  std::ofstream(dir / "results.json") << results.dump(2) << "\n";
}

std::string add_synthetic_run(storage::RunStore& store, const SyntheticRunSpec& spec) {
  const std::string id = store.create_run("dynamic", "SYNTH-0001", "bench: sim\n");
  const auto paths = store.paths(id);
  SyntheticRunSpec files = spec;
  write_synthetic_run_files(paths.dir, files);
  nlohmann::json results;
  std::ifstream(paths.dir / "results.json") >> results;
  store.write_results(id, results);
  store.finish_run(id, storage::RunStatus::kComplete, {}, true);
  return id;
}

}  // namespace wavebench::benchmarks
