#include "wavebench/twin/unit_twin_store.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <stdexcept>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/config/twin_case_writer.hpp"
#include "wavebench/model/angle_units.hpp"
#include "wavebench/storage/atomic_file.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::twin {
namespace {

// A figure of results.json: a number or an uncertain figure's "value".
std::optional<double> figure(const nlohmann::json& j) {
  if (j.is_number()) return j.get<double>();
  if (j.is_object() && j.contains("value") && j["value"].is_number()) {
    return j["value"].get<double>();
  }
  return std::nullopt;
}

// The torsional loop's catalogue curve and backlash from a torsional run's results.json.
UnitTwinStart loop_start(const std::filesystem::path& results_file) {
  UnitTwinStart start;
  std::ifstream in(results_file);
  if (!in) return start;
  const auto results = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!results.is_object() || !results.contains("torsional")) return start;
  const auto& t = results["torsional"];
  if (t.contains("stiffness") && t["stiffness"].is_object()) {
    const auto& s = t["stiffness"];
    const auto get = [&](const char* key) {
      return s.contains(key) ? figure(s[key]) : std::nullopt;
    };
    const auto k1 = get("k1_nm_per_rad"), k2 = get("k2_nm_per_rad"), k3 = get("k3_nm_per_rad");
    const auto t1 = get("t1_nm"), t2 = get("t2_nm");
    if (k1 && k2 && k3 && t1 && t2) {
      start.loop_stiffness = model::ThreeSegmentStiffness{*k1, *t1, *k2, *t2, *k3};
    }
  }
  if (t.contains("backlash_arcmin")) {
    if (const auto b = figure(t["backlash_arcmin"]))
      start.loop_backlash_rad = *b * model::kRadPerArcmin;
  }
  return start;
}

}  // namespace

std::string unit_folder_name(const std::string& serial) {
  if (serial.empty() || serial.size() > 64) {
    throw std::invalid_argument("unit serial '" + serial.substr(0, 80) +
                                "': expected 1 to 64 characters");
  }
  std::string out;
  for (const unsigned char c : serial) {
    if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
        c == '-') {
      out.push_back(static_cast<char>(c));
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    }
  }
  return out;
}

std::filesystem::path unit_twin_dir(const std::filesystem::path& store_root,
                                    const std::string& serial) {
  return store_root / "units" / unit_folder_name(serial);
}

std::optional<UnitTwin> load_unit_twin(const std::filesystem::path& store_root,
                                       const std::string& serial, double ratio) {
  const auto dir = unit_twin_dir(store_root, serial);
  std::error_code ec;
  if (!std::filesystem::exists(dir / "twin.json", ec)) return std::nullopt;
  UnitTwin unit;
  unit.case_file = dir / "twin.yaml";
  const auto refuse = [&](const std::filesystem::path& file, const std::string& why) {
    return std::runtime_error("unit twin of '" + serial + "': " + file.string() +
                              " not readable: " + why);
  };
  try {
    // Ours, but a file on disk all the same: bounded before it is parsed.
    constexpr std::uintmax_t kMaxProvenanceBytes = 1u << 20;
    if (std::filesystem::file_size(dir / "twin.json") > kMaxProvenanceBytes) {
      throw std::runtime_error("larger than 1 MiB");
    }
    std::ifstream in(dir / "twin.json");
    unit.provenance = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw refuse(dir / "twin.json", e.what());
  }
  if (!unit.provenance.is_object() || unit.provenance.value("schema", "") != kUnitTwinSchema) {
    throw refuse(dir / "twin.json", std::string("expected schema ") + kUnitTwinSchema);
  }
  try {
    unit.twin = config::load_twin_case(unit.case_file);
  } catch (const std::exception& e) {
    throw refuse(unit.case_file, e.what());
  }
  if (std::abs(unit.twin.gear.geometry.ratio - ratio) > 1e-9 * ratio) {
    throw std::runtime_error("unit twin of '" + serial + "' (" + unit.case_file.string() +
                             "): ratio " + std::to_string(unit.twin.gear.geometry.ratio) +
                             ", the bench's is " + std::to_string(ratio));
  }
  const auto delay = unit.provenance.find("input_latch_delay_s");
  if (delay != unit.provenance.end() && delay->is_number() &&
      std::abs(delay->get<double>()) < 1.0) {
    unit.solver.input_latch_delay_s = delay->get<double>();
  }
  return unit;
}

std::optional<UnitTwinUpdate> update_unit_twin(
    const storage::RunStore& store, const std::string& serial, const model::GearParams& nominal,
    const metrology::GearSense& sense, const std::string& bench_name,
    const CalibratedRun& just_calibrated, const TwinCalibrationOptions& options) {
  const auto dir = unit_twin_dir(store.root(), serial);
  // The newest complete run of each procedure of the unit.
  storage::RunQuery query;
  query.unit_serial = serial;
  query.status = storage::RunStatus::kComplete;
  std::map<std::string, storage::RunRecord> newest;
  for (const auto& run : store.list_runs(query)) {  // newest first
    if (!newest.contains(run.procedure)) newest.emplace(run.procedure, run);
  }
  UnitTwinUpdate update;
  UnitTwinStart start;
  if (newest.size() == 1 && just_calibrated.calibration != nullptr &&
      newest.begin()->second.id == just_calibrated.run_id) {
    // The unit's only run: its own calibration is the unit's twin.
    const TwinCalibration& c = *just_calibrated.calibration;
    auto& cal = update.calibration;
    cal.nominal = nominal;
    cal.calibrated = c.calibrated;
    cal.calibrated.name = nominal.name + " (unit twin)";
    cal.solver = c.solver;
    cal.fitted = c.fitted;
    cal.orders = c.orders;
    cal.passes = c.passes;
    cal.stiffness_factor = small_twist_stiffness_ratio(nominal, c.calibrated);
    UnitRunResidual r;
    r.run_id = just_calibrated.run_id;
    r.procedure = just_calibrated.procedure;
    r.samples = c.after.samples;
    r.after = c.after;
    r.noise_floor_arcsec = c.noise_floor_arcsec;
    cal.runs.push_back(std::move(r));
  } else {
    // The samples stay in their pages' vectors (a moved vector keeps its buffer: the spans
    // hold). A long run (an endurance run) contributes its first kMaxUnitTwinSamplesPerRun
    // samples: the replays hold every sample of every run in memory at once.
    std::vector<storage::SampleLogPage> logs;
    std::vector<UnitRunSamples> runs;
    for (const auto& [procedure, run] : newest) {
      const auto paths = store.paths(run.id);
      std::error_code ec;
      if (!std::filesystem::exists(paths.samples, ec)) continue;
      logs.push_back(storage::read_sample_log_page(paths.samples, 0, kMaxUnitTwinSamplesPerRun));
      runs.push_back({run.id, procedure, logs.back().samples});
      if (procedure == "torsional") start = loop_start(paths.results);
    }
    if (runs.empty()) return std::nullopt;
    update.calibration = calibrate_unit_twin(nominal, sense, runs, start, options);
  }
  const auto& cal = update.calibration;
  update.provenance = to_json(cal);
  update.provenance["schema"] = kUnitTwinSchema;
  update.provenance["unit_serial"] = serial;
  update.provenance["bench"] = bench_name;
  update.provenance["nominal_twin"] = nominal.name;
  update.provenance["case"] = "twin.yaml";
  update.provenance["stiffness_start"] = start.loop_stiffness ? "torsional loop" : "nominal";

  config::TwinCase twin;
  twin.gear = cal.calibrated;
  std::string comment = "The twin of unit '" + serial + "' (issue #11), calibrated over";
  for (const auto& r : cal.runs) {
    char line[160];
    std::snprintf(line, sizeof line, "\n  %s run %s: residual RMS %.3f arcsec (floor %.3f)",
                  r.procedure.c_str(), r.run_id.c_str(), r.after.rms_arcsec, r.noise_floor_arcsec);
    comment += line;
  }
  comment += "\nFrom the nominal twin '" + nominal.name + "'. Its provenance: twin.json.";
  std::filesystem::create_directories(dir);
  update.case_file = dir / "twin.yaml";
  storage::write_file_atomically(update.case_file, config::write_twin_case_yaml(twin, comment));
  storage::write_file_atomically(dir / "twin.json", update.provenance.dump(2) + "\n");
  return update;
}

}  // namespace wavebench::twin
