#pragma once
// Endurance (issue #12): hours at a constant input speed and brake load, the TE of every output
// revolution analysed on its own as the run goes: mean, p2p and RMS, the mesh lines (orders
// k·z_F of the output), the brake's coil temperature at the revolution's end and the input
// speed; a trend over the run. Streaming: the samples of one revolution are kept until it is
// analysed (on a worker thread, at most kMaxPendingRevolutions behind), never the run's.
//
// Each revolution is the dynamic procedure's analysis (metrology::analyse_dynamic_te) of the
// samples from its first one to the first one at or past one whole output turn later; that
// sample also starts the next revolution. The twin's residual per revolution is the twin's own
// (results.twin.diagnosis.revolutions): the report draws the two trends together.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "wavebench/bench/bench.hpp"
#include "wavebench/metrology/dynamic_te_analysis.hpp"
#include "wavebench/procedures/option_reader.hpp"
#include "wavebench/procedures/procedure_progress.hpp"
#include "wavebench/procedures/run_plan.hpp"

namespace wavebench::procedures {

struct EnduranceOptions {
  double input_rpm = 100;
  double run_in_s = 2.0;
  // 60 is an hour at 100 rpm on a gear of N = 100.
  int output_revolutions = 60;
  double load_nm = 0;
  int mesh_harmonics = 3;  // mesh lines tracked: orders z_F, 2·z_F, ...

  static EnduranceOptions from_json(const nlohmann::json& options);
  static std::vector<OptionSpec> schema();
  nlohmann::json to_json() const;
};

// One output revolution of the trend.
struct RevolutionTrend {
  int revolution = 0;                 // 1-based, from the start of the recording
  double t_start_s = 0, t_end_s = 0;  // bench time of its first and last sample
  std::int64_t first_receive_time_ns = 0, last_receive_time_ns = 0;  // in samples.wbs
  std::size_t samples = 0;                                           // analysed
  double mean_arcsec = 0, p2p_arcsec = 0, rms_arcsec = 0;
  double input_speed_hz = 0;
  std::vector<double> mesh_arcsec;            // amplitude at k·z_F, k = 1..mesh_harmonics
  std::optional<double> brake_temperature_c;  // the controller's readback at its end
  std::string error;  // the analysis refused the revolution (figures then 0)
};

struct EnduranceOutcome {
  std::vector<RevolutionTrend> revolutions;
  std::vector<int> mesh_orders;  // output orders of mesh_arcsec
  metrology::GearTeeth teeth;
  std::size_t samples = 0;  // recorded
  // results.json "endurance": the trend table and its summary (first, last, largest p2p, the
  // drift of the mean, the brake's temperature rise).
  nlohmann::json to_json() const;
};

// The figures of one revolution from its samples (the analysis a worker runs).
RevolutionTrend analyse_revolution(std::vector<storage::SyncSample> samples,
                                   const bench::BenchDescription& bench,
                                   const metrology::GearTeeth& teeth, int mesh_harmonics);

class EnduranceProcedure {
 public:
  // Where run()'s outcome goes in results.json.
  static constexpr std::string_view kResultsSection = "endurance";
  static constexpr std::size_t kMaxPendingRevolutions = 2;

  explicit EnduranceProcedure(EnduranceOptions options);
  RunPlan plan(const bench::BenchDescription& bench) const;
  // Throws bench::BenchAborted when the bench trips.
  EnduranceOutcome run(bench::Bench& bench, const ProcedureProgress& progress = {}) const;

 private:
  EnduranceOptions options_;
};

}  // namespace wavebench::procedures
