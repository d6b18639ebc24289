#pragma once
// One twin per unit serial (issue #11), kept beside the runs it came from:
//
//   <run store root>/units/<serial>/twin.yaml   a twin case (configs/twin schema, loadable by
//                                               config::load_twin_case): the unit's gear
//   <run store root>/units/<serial>/twin.json   where it came from (schema wavebench.unit-twin/1):
//                                               the runs, their residual before/after, the
//                                               input latch delay, the bench
//
// The serial is the folder's name with every character outside [A-Za-z0-9_-] written as %XX
// (a serial may hold '/' and '.'; the folder never leaves units/). Both files are written
// atomically, the case first: a reader that finds twin.json finds the case it describes.
//
// After every complete run of a unit, update_unit_twin() calibrates the unit's twin anew over
// the newest complete run of each procedure of that unit (calibrate_unit_twin); the twin
// beside the bench on the unit's next run is that twin (load_unit_twin).

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/config/twin_case.hpp"
#include "wavebench/metrology/gear_sense.hpp"
#include "wavebench/storage/run_store.hpp"
#include "wavebench/twin/measured_drive_twin.hpp"
#include "wavebench/twin/twin_calibrator.hpp"

namespace wavebench::twin {

inline constexpr const char* kUnitTwinSchema = "wavebench.unit-twin/1";
// 10 minutes at 1 kHz: what one run contributes at most (its first samples), so that the
// calibration's memory is bounded whatever the runs' length (~60 MB per run with its replays).
inline constexpr std::size_t kMaxUnitTwinSamplesPerRun = 600'000;

// "A/B.1" -> "A%2FB%2E1". Throws std::invalid_argument for an empty serial or one longer than
// 64 characters.
std::string unit_folder_name(const std::string& serial);
std::filesystem::path unit_twin_dir(const std::filesystem::path& store_root,
                                    const std::string& serial);

struct UnitTwin {
  config::TwinCase twin;
  TwinSolverOptions solver;   // the nominal options with the unit's input latch delay
  nlohmann::json provenance;  // twin.json
  std::filesystem::path case_file;
};

// The unit's twin, or nullopt when it has none. Throws std::runtime_error naming the file when
// one is there but cannot be read (a damaged case, a ratio other than `ratio`).
std::optional<UnitTwin> load_unit_twin(const std::filesystem::path& store_root,
                                       const std::string& serial, double ratio);

struct UnitTwinUpdate {
  UnitTwinCalibration calibration;
  std::filesystem::path case_file;
  nlohmann::json provenance;
};

// The run that was just calibrated (run_executor): when the unit's newest runs are that run
// alone, its calibration is the unit's twin and nothing is replayed again.
struct CalibratedRun {
  std::string run_id;
  std::string procedure;
  const TwinCalibration* calibration = nullptr;
};

// Calibrates the unit's twin over its newest complete run of each procedure (the runs' sample
// logs, the first kMaxUnitTwinSamplesPerRun samples of each; a torsional run's loop seeds the
// stiffness and backlash from its results.json) and writes it. `nominal` is the bench's twin case
// (the fit starts from it). Returns nullopt when the unit has no complete run with a sample log.
// Throws on a fit or write failure (nothing half-written: the files are replaced atomically).
std::optional<UnitTwinUpdate> update_unit_twin(
    const storage::RunStore& store, const std::string& serial, const model::GearParams& nominal,
    const metrology::GearSense& sense, const std::string& bench_name,
    const CalibratedRun& just_calibrated = {}, const TwinCalibrationOptions& options = {});

}  // namespace wavebench::twin
