#pragma once
// What a run folder holds, read for a report. Every file is optional except that a folder
// with none of status.json, results.json and samples.wbs is not a run folder; a file that is
// missing or unreadable becomes a note on the report, never an exception.
//
//   status.json   storage::to_json(RunRecord): id, procedure, unit_serial, status, reason, ...
//   results.json  the procedure's results (sections found by shape, see the section helpers)
//   samples.wbs   storage::SampleLog, every SYNC sample
//   twin.csv      t, index, measured_te_arcsec, predicted_te_arcsec, residual_arcsec

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/procedures/gear_sense.hpp"
#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::report {

struct TwinTrace {  // columns of twin.csv; a column absent from the file stays empty
  std::vector<double> t, measured_te_arcsec, predicted_te_arcsec, residual_arcsec;
};

struct RunFolder {
  std::filesystem::path dir;
  nlohmann::json status = nlohmann::json::object();
  nlohmann::json results = nlohmann::json::object();
  std::vector<storage::SyncSample> samples;
  std::optional<TwinTrace> twin;
  // The gear sense from results.json ("gear" or any object with "ratio"), or estimated from
  // the samples (θ_in against θ_out) when the results do not carry it.
  std::optional<procedures::GearSense> sense;
  bool sense_estimated = false;
  std::vector<std::string> notes;  // what was missing or unreadable, shown on the report

  // A status.json field as text, falling back to results.json, then to `fallback`.
  std::string field(const std::string& key, const std::string& fallback = {}) const;
  std::string run_id() const;  // status id, else the folder name
};

// Throws std::invalid_argument naming the path when it is not a directory or holds none of
// status.json, results.json, samples.wbs. Without `read_samples` (a summary needs only the
// JSON files) samples.wbs is not read and no gear sense is estimated from it.
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

// θ_out against θ_in fitted over the samples with both angles valid; N rounded to a whole or
// half ratio as gears have. nullopt when the output hardly moved.
std::optional<procedures::GearSense> estimate_gear_sense(
    const std::vector<storage::SyncSample>& samples);

}  // namespace wavebench::report
