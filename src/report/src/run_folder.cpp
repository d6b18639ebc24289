#include "wavebench/report/run_folder.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "wavebench/storage/sample_log.hpp"

namespace wavebench::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A JSON object from a file; a missing file is nullopt, a malformed one a note.
std::optional<json> read_json_object(const fs::path& path, std::vector<std::string>& notes) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path);
  json j = json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) {
    notes.push_back(path.filename().string() + " is not a JSON object; its sections are left out");
    return std::nullopt;
  }
  return j;
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, sep)) out.push_back(cell);
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

std::optional<TwinTrace> read_twin_csv(const fs::path& path, std::vector<std::string>& notes) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) {
    notes.push_back("twin.csv is empty; the twin plot is left out");
    return std::nullopt;
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const auto header = split(line, ',');
  TwinTrace trace;
  std::vector<std::vector<double>*> columns(header.size(), nullptr);
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == "t") columns[i] = &trace.t;
    if (header[i] == "measured_te_arcsec") columns[i] = &trace.measured_te_arcsec;
    if (header[i] == "predicted_te_arcsec") columns[i] = &trace.predicted_te_arcsec;
    if (header[i] == "residual_arcsec") columns[i] = &trace.residual_arcsec;
  }
  std::size_t bad_rows = 0;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const auto cells = split(line, ',');
    if (cells.size() != header.size()) {
      ++bad_rows;
      continue;
    }
    std::vector<double> values(cells.size());
    bool ok = true;
    for (std::size_t i = 0; i < cells.size() && ok; ++i) {
      if (!columns[i]) continue;
      char* end = nullptr;
      values[i] = std::strtod(cells[i].c_str(), &end);
      ok = end != cells[i].c_str() && *end == '\0';
    }
    if (!ok) {
      ++bad_rows;
      continue;
    }
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (columns[i]) columns[i]->push_back(values[i]);
    }
  }
  if (bad_rows > 0) {
    notes.push_back("twin.csv: " + std::to_string(bad_rows) + " malformed rows skipped");
  }
  if (trace.t.empty()) {
    notes.push_back("twin.csv has no usable rows (needs column t); the twin plot is left out");
    return std::nullopt;
  }
  return trace;
}

// A section of results.json by its name in the schema (docs/formats/results.schema.json), of
// the JSON type the schema gives it: the report never guesses a section from its shape.
const json* section(const json& results, const std::string& key, json::value_t type) {
  if (!results.is_object()) return nullptr;
  const auto it = results.find(key);
  return it != results.end() && it->type() == type ? &*it : nullptr;
}

std::optional<procedures::GearSense> sense_from_results(const json& results) {
  const json* g = section(results, "gear", json::value_t::object);
  if (!g || !number(*g, "ratio")) return std::nullopt;
  procedures::GearSense sense;
  sense.ratio = (*g)["ratio"].get<double>();
  if (auto s = number(*g, "direction_sign")) sense.direction_sign = *s < 0 ? -1 : 1;
  if (!(sense.ratio > 0)) return std::nullopt;
  return sense;
}

}  // namespace

std::optional<double> number(const json& object, const std::string& key) {
  if (!object.is_object()) return std::nullopt;
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number()) return std::nullopt;
  const double v = it->get<double>();
  if (!std::isfinite(v)) return std::nullopt;
  return v;
}

std::string RunFolder::field(const std::string& key, const std::string& fallback) const {
  for (const json* source : {&status, &results}) {
    const auto it = source->find(key);
    if (it == source->end() || it->is_null()) continue;
    if (it->is_string()) {
      if (!it->get<std::string>().empty()) return it->get<std::string>();
      continue;
    }
    return it->dump();
  }
  return fallback;
}

std::string RunFolder::run_id() const {
  return field("id", field("run_id", dir.filename().string()));
}

RunFolder read_run_folder(const fs::path& dir, bool read_samples) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw std::invalid_argument("run folder '" + dir.string() + "': not a directory");
  }
  const bool any = fs::exists(dir / "status.json", ec) || fs::exists(dir / "results.json", ec) ||
                   fs::exists(dir / "samples.wbs", ec);
  if (!any) {
    throw std::invalid_argument("run folder '" + dir.string() +
                                "': holds none of status.json, results.json, samples.wbs; "
                                "expected a run folder written by `wavebench run`");
  }
  RunFolder run;
  run.dir = dir;
  if (auto s = read_json_object(dir / "status.json", run.notes)) {
    run.status = std::move(*s);
  } else if (!fs::exists(dir / "status.json", ec)) {
    run.notes.push_back("no status.json");
  }
  if (auto r = read_json_object(dir / "results.json", run.notes)) {
    run.results = std::move(*r);
  } else if (!fs::exists(dir / "results.json", ec)) {
    run.notes.push_back("no results.json; the result tables are left out");
  }
  if (!read_samples) {
    // A summary reads the JSON files only.
  } else if (fs::exists(dir / "samples.wbs", ec)) {
    try {
      auto log = storage::read_sample_log(dir / "samples.wbs");
      run.samples = std::move(log.samples);
      if (log.torn_tail_bytes > 0) {
        run.notes.push_back("samples.wbs ends in a torn record (" +
                            std::to_string(log.torn_tail_bytes) + " bytes ignored)");
      }
      if (log.corrupt_record) {
        run.notes.push_back("samples.wbs: record " + std::to_string(log.corrupt_at_index) +
                            " failed its checksum; samples after it are left out");
      }
    } catch (const std::exception& e) {
      run.notes.push_back(std::string("samples.wbs unreadable: ") + e.what());
    }
  } else {
    run.notes.push_back("no samples.wbs; plots of the raw record are left out");
  }
  run.twin = read_twin_csv(dir / "twin.csv", run.notes);
  run.sense = sense_from_results(run.results);
  if (!run.sense && !run.samples.empty()) {
    run.sense = estimate_gear_sense(run.samples);
    run.sense_estimated = run.sense.has_value();
    if (run.sense_estimated) {
      run.notes.push_back("gear ratio not in results.json; estimated from the samples as " +
                          std::to_string(run.sense->ratio));
    }
  }
  return run;
}

const json* static_passes(const json& results) {
  return section(results, "static", json::value_t::array);
}
const json* lost_motion_profiles(const json& results) {
  return section(results, "lost_motion", json::value_t::array);
}
const json* load_shifts(const json& results) {
  return section(results, "load_shift", json::value_t::array);
}

const json* dynamic_section(const json& results) {
  return section(results, "dynamic", json::value_t::object);
}

const json* lost_motion_fit(const json& results) {
  return section(results, "lost_motion_fit", json::value_t::object);
}

const json* twin_section(const json& results) {
  return section(results, "twin", json::value_t::object);
}

std::optional<procedures::GearSense> estimate_gear_sense(
    const std::vector<storage::SyncSample>& samples) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  double lo = 0, hi = 0;
  for (const auto& s : samples) {
    if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid)) continue;
    const double x = s.theta_out_rad, y = s.theta_in_rad;
    if (n == 0) lo = hi = x;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  // Below about a degree of output travel the TE itself would bend the slope.
  if (n < 3 || hi - lo < 0.02) return std::nullopt;
  const double var = sxx - sx * sx / n;
  if (!(var > 0)) return std::nullopt;
  const double slope = (sxy - sx * sy / n) / var;  // s·N
  double ratio = std::abs(slope);
  if (!(ratio > 0) || !std::isfinite(ratio)) return std::nullopt;
  const double half_steps = std::round(ratio * 2) / 2;
  if (std::abs(half_steps - ratio) < 0.01 * ratio) ratio = half_steps;
  procedures::GearSense sense;
  sense.ratio = ratio;
  sense.direction_sign = slope < 0 ? -1 : 1;
  return sense;
}

}  // namespace wavebench::report
