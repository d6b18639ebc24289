#pragma once
// Dynamic TE (bench.md §4): the input at constant speed (profile velocity, default 100 rpm),
// a run-in, then at least one whole output revolution sampled at the SYNC rate. TE against
// time and output angle, the spectrum in Hz and in orders, the peaks named (output 1/rev, the
// mesh, their harmonics, the twin's components) and the twin's components above Nyquist listed
// as aliased.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string_view>
#include <vector>

#include "wavebench/bench/bench.hpp"
#include "wavebench/metrology/dynamic_te_analysis.hpp"
#include "wavebench/metrology/dynamic_te_input.hpp"
#include "wavebench/procedures/option_reader.hpp"
#include "wavebench/procedures/procedure_progress.hpp"
#include "wavebench/procedures/run_plan.hpp"

namespace wavebench::procedures {

struct DynamicTeOptions {
  double input_rpm = 100;
  double run_in_s = 2.0;
  // Recorded, at least one whole revolution. Two by default: with one the order resolution is
  // a whole order and the Hann window merges the z_F and z_C lines (orders 200 and 202).
  double output_revolutions = 2.0;
  double load_nm = 0;  // brake torque during the run
  int max_peaks = 12;
  int harmonics = 3;

  static DynamicTeOptions from_json(const nlohmann::json& options);
  // The options as the console shows them: one entry per key from_json accepts, in order.
  static std::vector<OptionSpec> schema();
  nlohmann::json to_json() const;
};

struct DynamicTeOutcome {
  metrology::DynamicTeResult result;
  std::size_t samples = 0;  // recorded
  std::size_t skipped_invalid = 0, skipped_out_of_order = 0, missed_cycles = 0;
  std::size_t skipped_not_advancing = 0;
  // The analysed record in samples.wbs: receive_time_ns of its first and last sample.
  std::int64_t first_receive_time_ns = 0, last_receive_time_ns = 0;
  metrology::GearTeeth teeth;
  // results.json "dynamic": the analysis (peaks, aliased, mean/p2p/RMS) with the sample
  // counts, the order spectrum and a TE trace decimated for plotting.
  nlohmann::json to_json() const;
};

// The components the twin predicts (its TE terms at non-zero frequency), plus the tooth-mesh
// line U·z_C per wave-generator revolution when the twin has no term there: the kinematics
// predict it whatever its amplitude.
std::vector<metrology::PredictedComponent> predicted_components(
    const model::GearParams& twin, const metrology::GearTeeth& teeth);
// The teeth from the twin's geometry, or from N (z_F = U·N, z_C = z_F + U) when it has none.
metrology::GearTeeth gear_teeth(const model::GearParams& twin, double ratio);

class DynamicTeProcedure {
 public:
  // Where run()'s outcome goes in results.json.
  static constexpr std::string_view kResultsSection = "dynamic";
  explicit DynamicTeProcedure(DynamicTeOptions options);
  // What run() will command on `bench` and for how long, without touching it. Throws
  // std::invalid_argument where run() would refuse the options on this bench.
  RunPlan plan(const bench::BenchDescription& bench) const;
  // Throws bench::BenchAborted when the bench trips.
  DynamicTeOutcome run(bench::Bench& bench, const ProcedureProgress& progress = {}) const;

 private:
  DynamicTeOptions options_;
};

}  // namespace wavebench::procedures
