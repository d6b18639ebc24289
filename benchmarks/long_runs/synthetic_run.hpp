#pragma once
// A dynamic run folder of any length without running the bench for it (issue #12: a one-hour
// run is 3.6 M samples): samples.wbs through storage::SampleLogWriter, twin.csv of as many rows
// in twin_overlay's format, and results.json (a template adapted, or a small built-in one).
//
// The record: θ_in ramps up to `input_rpm`, turns steadily, ramps down; θ_out = θ_in/N + TE
// with TE = 1/rev, 2/rev and 2N/rev lines (arcsec) plus a little noise; SYNC receive times at
// `rate_hz` with a few microseconds of jitter; a missed SYNC every 100,000 samples.
// Deterministic: the same spec writes the same bytes.

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "wavebench/storage/run_store.hpp"

namespace wavebench::benchmarks {

struct SyntheticRunSpec {
  std::size_t samples = 3'600'000;
  double rate_hz = 1000;
  double input_rpm = 100;
  double ratio = 100;
  double ramp_s = 2;  // run-in and stop, each
  // TE line amplitudes [arcsec] at output orders 1, 2 and 2N.
  double te_1_arcsec = 4, te_2_arcsec = 2.5, te_mesh_arcsec = 1.5;
  double noise_arcsec = 0.05;
  bool twin_csv = true;
  // results.json to adapt (its "dynamic.samples" and "gear.ratio" set from the spec); null:
  // a built-in one with the gear, the dynamic section's lines and the acquisition.
  nlohmann::json results_template;
};

// TE of the record at output angle θ2 [rad], arcsec, without the noise.
double synthetic_te_arcsec(const SyntheticRunSpec& spec, double theta_out_rad);

// samples.wbs, twin.csv and results.json into `dir` (created; existing files replaced).
void write_synthetic_run_files(const std::filesystem::path& dir, const SyntheticRunSpec& spec);

// The same as a run of `store` (created, finished complete). Returns its id.
std::string add_synthetic_run(storage::RunStore& store, const SyntheticRunSpec& spec);

}  // namespace wavebench::benchmarks
