#pragma once
// Calibrating the twin to a run (bench.md §5): the twin is replayed over the run's samples,
// and a linear least-squares fit of the residual (metrology::fit_te_harmonics with extra
// regressors) corrects, in one solve,
//   - the TE harmonics on the ordered harmonic basis sin/cos(a·θ1 + b·θ2) (the nominal terms'
//     orders plus the standard families that the run's angles resolve) and a constant (the
//     encoder zero offset, written as an order-(0, 0) term),
//   - the backlash (regressor: the contact flank ±1/2, fitted only when both flanks carry
//     samples),
//   - the stiffness (regressor: the twin's spring twist x; k → k/(1 + ε)), fitted only when
//     the gear torque varies over the run (several loads).
//   - the input latch delay (regressor: ω1/N, TwinSolverOptions), fitted only when the
//     speed varies.
// TE = −e − Δ with Δ = x + flank·b/2 makes the residual linear in all of them. A static run's
// estimate_stiffness_backlash() (when given) sets the starting backlash and stiffness. The fit
// and replay repeat `passes` times (the contact and twist move with the parameters); the
// calibrated parameters are those of the replay with the lowest residual RMS, the nominal
// ones included ("no_improvement" in `fitted` then).

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/model/gear_params.hpp"
#include "wavebench/model/simulation.hpp"
#include "wavebench/metrology/static_te_statistics.hpp"
#include "wavebench/metrology/twin_calibration.hpp"
#include "wavebench/storage/sync_sample.hpp"
#include "wavebench/twin/measured_drive_twin.hpp"

namespace wavebench::twin {

// The samples a run's own calibration fits at most (the first ones: 2 min at 1 kHz, two output
// revolutions at 100 rpm and N = 100). Its samples and rows are held in memory (~300 bytes a
// sample), so this keeps a run of hours in the memory of a run of minutes (issue #12).
inline constexpr std::size_t kMaxCalibrationSamples = 120'000;

struct TwinCalibrationOptions {
  TwinSolverOptions solver;
  int passes = 2;
  std::vector<metrology::HarmonicOrder> extra_orders;
  // An order enters the fit only when its phase a·θ1 + b·θ2 sweeps this much over the run.
  double min_phase_span_rad = 6.283185307179586;
  // Backlash is fitted only when each flank holds this fraction of the samples.
  double min_flank_fraction = 0.05;
  // The input latch delay (TwinSolverOptions) is fitted only when the output speed (2nd to
  // 98th percentile) spans this much [rad/s]: at one speed it is a TE offset.
  double min_speed_span_rad_s = 0.05;
  // Stiffness is fitted only when the gear torque (2nd to 98th percentile) spans this much:
  // at one load the twist is confounded with the TE offset.
  double min_torque_span_nm = 5;
  // A catalogue curve's K1, K2 and K3 are fitted each on its own only when every segment
  // holds this fraction of the rows well inside it (a locked-output loop); otherwise one
  // factor scales the whole law (a static run at two loads cannot tell the segments apart).
  double min_segment_fraction = 0.02;
};

struct TwinCalibration {
  model::GearParams nominal;
  model::GearParams calibrated;
  metrology::TwinResidual before;  // nominal twin replayed over the run
  metrology::TwinResidual after;   // calibrated twin replayed over the same samples
  double stiffness_factor = 1;      // calibrated / nominal stiffness
  // The solver options of the calibrated replay, with the fitted input latch delay (a property
  // of the bench's sampling, not of the gear: it is not in the config file).
  TwinSolverOptions solver;
  std::vector<std::string> fitted;  // what the fit changed: te_harmonics, offset, backlash, ...
  std::vector<metrology::HarmonicOrder> orders;  // the harmonic basis used
  int passes = 0;
  // The sensors' noise in the measured TE, estimated from the run itself (see
  // estimate_te_noise_floor): what the residual cannot go below.
  double noise_floor_arcsec = 0;
};

// The white part of the residual (measured − predicted TE) over consecutive samples, from its
// third differences: sqrt(mean(Δ³r²)/20), exact for white noise, while a smooth line of
// frequency f adds only (2π·f/f_s)³ of its amplitude. With the calibrated twin the residual's
// lines are small, so this is the sensors' noise in the TE. 0 without four consecutive
// samples.
double estimate_te_noise_floor_arcsec(std::span<const TwinPoint> points);

// The calibrated law's small-twist stiffness over the nominal's (1 when either is not elastic).
double small_twist_stiffness_ratio(const model::GearParams& nominal,
                                   const model::GearParams& calibrated);

// twin.csv of `gear` replayed over `samples` (twin_overlay.hpp), e.g. a calibration's
// (twin-calibrated.csv), written as the replay goes. Returns the rows written.
std::uint64_t write_replay_csv(const std::filesystem::path& file, const model::GearParams& gear,
                               const metrology::GearSense& sense,
                               std::span<const storage::SyncSample> samples,
                               const TwinSolverOptions& solver);

// Throws std::invalid_argument when fewer samples than unknowns carry a measured TE.
TwinCalibration calibrate_twin(const model::GearParams& nominal, const metrology::GearSense& sense,
                               std::span<const storage::SyncSample> samples,
                               const metrology::StaticTeResult* static_run = nullptr,
                               const TwinCalibrationOptions& options = {});

// One twin per unit (issue #11): the calibration above over several runs of the same unit in
// one solve (a locked-output loop, a static run, a dynamic run, ...): their rows share the
// gear's harmonics, offset, backlash and stiffness and the bench's input latch delay, so each
// run pins what it resolves (the loop the stiffness of each segment, the static run the TE at
// standstill on both flanks, the dynamic run the harmonics in motion and the latch delay against
// the standstill). The best replay is the one with the lowest RMS residual over all runs.
struct UnitRunSamples {
  std::string run_id;
  std::string procedure;
  std::span<const storage::SyncSample> samples;
};
// Where the fit starts: the torsional loop's catalogue curve and backlash, when there is one.
struct UnitTwinStart {
  std::optional<model::ThreeSegmentStiffness> loop_stiffness;
  std::optional<double> loop_backlash_rad;
};
struct UnitRunResidual {
  std::string run_id;
  std::string procedure;
  std::size_t samples = 0;
  metrology::TwinResidual after;  // the unit twin over the run
  double noise_floor_arcsec = 0;   // estimated from the unit twin's residual
};
struct UnitTwinCalibration {
  model::GearParams nominal;
  model::GearParams calibrated;
  TwinSolverOptions solver;  // with the fitted input latch delay
  std::vector<UnitRunResidual> runs;
  std::vector<std::string> fitted;
  std::vector<metrology::HarmonicOrder> orders;
  int passes = 0;
  double stiffness_factor = 1;
};
// Throws std::invalid_argument when `runs` is empty, the loop's curve is not one (K ≤ 0,
// T2 ≤ T1) or fewer samples than unknowns carry a measured TE.
UnitTwinCalibration calibrate_unit_twin(const model::GearParams& nominal,
                                        const metrology::GearSense& sense,
                                        std::span<const UnitRunSamples> runs,
                                        const UnitTwinStart& start = {},
                                        const TwinCalibrationOptions& options = {});

// Per run: the unit twin's residual and its floor; the stiffness law, backlash, latch delay,
// what was fitted and the TE terms.
nlohmann::json to_json(const UnitTwinCalibration& calibration);

// The calibrated gear as a twin case (configs/twin schema, loadable by load_twin_case), with
// the residual before/after in its header comment. Written atomically.
void write_calibrated_twin_config(const std::filesystem::path& file,
                                  const TwinCalibration& calibration,
                                  const model::SimulationOptions& solver = {});

// residual_before/after (mean, RMS, p2p arcsec), backlash, stiffness factor, the TE terms.
nlohmann::json to_json(const TwinCalibration& calibration);

}  // namespace wavebench::twin
