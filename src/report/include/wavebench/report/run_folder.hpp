#pragma once
// What a run folder holds, read for a report. Every file is optional except that a folder
// with none of status.json, results.json and samples.wbs is not a run folder; a file that is
// missing or unreadable becomes a note on the report, never an exception.
//
//   status.json   storage::to_json(RunRecord): id, procedure, unit_serial, status, reason, ...
//   results.json  the procedure's results (sections found by shape, see the section helpers)
//   samples.wbs   storage::SampleLog, every SYNC sample: read page by page, never whole (a
//                 one-hour run is 3.6 M samples); reading the folder counts what it holds and
//                 the plots read it again for what each needs (sample_log_scan.hpp)
//   twin.csv      t, index, measured_te_arcsec, predicted_te_arcsec, residual_arcsec: read line
//                 by line into min/max envelopes (twin_csv_envelope.hpp)

#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/metrology/gear_sense.hpp"
#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::report {

class InputSpeedSummary;  // dynamic_plot_data.hpp

// Columns of twin.csv as drawn: its rows while there are few, else the min/max envelope per
// pixel column (analysis::min_max_columns). A column absent from the file stays empty.
struct TwinTrace {
  std::vector<double> t, measured_te_arcsec, predicted_te_arcsec, residual_arcsec;
  std::size_t rows = 0;  // rows of the file behind them
};

// What one pass through samples.wbs counted: the report's facts, and the sizes the plots'
// passes need up front.
struct SampleLogFacts {
  std::uint64_t records = 0;     // intact records, up to a corrupt one
  std::uint64_t missed = 0;      // SYNC cycles missed (sum of missed_before)
  std::uint64_t incomplete = 0;  // records with a channel missing
  // Records with both angles valid and a time after the previous such record: what the
  // dynamic trace is made of (dynamic_trace).
  std::uint64_t angle_samples = 0;
  // What dynamic_plot_data() needs of the same pass (dynamic_plot_data.hpp).
  std::shared_ptr<const InputSpeedSummary> input_speeds;
};

// θ_out against θ_in fitted over the samples with both angles valid, fed one sample at a time;
// N rounded to a whole or half ratio as gears have. nullopt when the output hardly moved.
class GearSenseFit {
 public:
  void add(const storage::SyncSample& s);
  std::optional<metrology::GearSense> result() const;

 private:
  double n_ = 0, sx_ = 0, sy_ = 0, sxx_ = 0, sxy_ = 0, lo_ = 0, hi_ = 0;
};

struct RunFolder {
  std::filesystem::path dir;
  nlohmann::json status = nlohmann::json::object();
  nlohmann::json results = nlohmann::json::object();
  std::optional<SampleLogFacts> sample_log;  // when samples.wbs was read
  std::optional<TwinTrace> twin;
  // The gear sense from results.json ("gear" or any object with "ratio"), or estimated from
  // the samples (θ_in against θ_out) when the results do not carry it.
  std::optional<metrology::GearSense> sense;
  bool sense_estimated = false;
  std::vector<std::string> notes;  // what was missing or unreadable, shown on the report

  // A status.json field as text, falling back to results.json, then to `fallback`.
  std::string field(const std::string& key, const std::string& fallback = {}) const;
  std::string run_id() const;  // status id, else the folder name
  std::filesystem::path samples_path() const { return dir / "samples.wbs"; }
};

// Throws std::invalid_argument naming the path when it is not a directory or holds none of
// status.json, results.json, samples.wbs. Without `read_samples` (a summary needs only the
// JSON files) samples.wbs and twin.csv are not read and no gear sense is estimated.
RunFolder read_run_folder(const std::filesystem::path& dir, bool read_samples = true);

// Sections of results.json, found by shape at the top level or one level down so that the
// report does not depend on how a procedure nests them. nullptr when absent.
const nlohmann::json* static_passes(const nlohmann::json& results);         // "static": [...]
const nlohmann::json* lost_motion_profiles(const nlohmann::json& results);  // "lost_motion": [...]
const nlohmann::json* load_shifts(const nlohmann::json& results);           // "load_shift": [...]
// The dynamic analysis: an object with "peaks" and "rms_arcsec".
const nlohmann::json* dynamic_section(const nlohmann::json& results);
// The lost-motion fit: an object with "stiffness" holding "k1_nm_per_rad".
const nlohmann::json* lost_motion_fit(const nlohmann::json& results);
const nlohmann::json* twin_section(const nlohmann::json& results);  // "twin": {...}

// A number from a JSON value, nullopt when it is not a finite number.
std::optional<double> number(const nlohmann::json& object, const std::string& key);

// GearSenseFit over a record in memory.
std::optional<metrology::GearSense> estimate_gear_sense(
    const std::vector<storage::SyncSample>& samples);

}  // namespace wavebench::report
