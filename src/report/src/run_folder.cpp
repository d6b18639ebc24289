#include "wavebench/report/run_folder.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "wavebench/report/dynamic_plot_data.hpp"
#include "wavebench/report/figure.hpp"
#include "wavebench/report/sample_log_scan.hpp"
#include "wavebench/report/twin_csv_envelope.hpp"
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

// The first pass through samples.wbs: the facts, the gear sense fit and the sizes the plots'
// passes need, a page at a time.
SampleLogFacts count_sample_log(const fs::path& path, GearSenseFit& fit,
                                std::vector<std::string>& notes) {
  const auto head = storage::read_sample_log_page(path, 0, 0);
  SampleLogFacts facts;
  auto speeds = std::make_shared<InputSpeedSummary>(head.total_records);
  bool any_angles = false;
  std::int64_t last_angle_ns = 0;
  std::uint64_t record = 0;
  facts.records = scan_sample_log(path, 0, head.total_records, [&](const storage::SyncSample& s) {
    const std::uint64_t r = record++;
    facts.missed += s.missed_before;
    if (!s.complete()) ++facts.incomplete;
    fit.add(s);
    if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid)) return;
    // As dynamic_trace takes them: a time after the previous one's (the same seconds).
    const double t = 1e-9 * static_cast<double>(s.receive_time_ns);
    if (any_angles && t <= 1e-9 * static_cast<double>(last_angle_ns)) return;
    any_angles = true;
    last_angle_ns = s.receive_time_ns;
    ++facts.angle_samples;
    speeds->add(r, t, s.theta_in_rad);
  });
  facts.input_speeds = std::move(speeds);
  if (head.torn_tail_bytes > 0) {
    notes.push_back("samples.wbs ends in a torn record (" + std::to_string(head.torn_tail_bytes) +
                    " bytes ignored)");
  }
  if (facts.records < head.total_records) {
    notes.push_back("samples.wbs: record " + std::to_string(facts.records) +
                    " failed its checksum; samples after it are left out");
  }
  return facts;
}

// A section of results.json by its name in the schema (docs/formats/results.schema.json), of
// the JSON type the schema gives it: the report never guesses a section from its shape.
const json* section(const json& results, const std::string& key, json::value_t type) {
  if (!results.is_object()) return nullptr;
  const auto it = results.find(key);
  return it != results.end() && it->type() == type ? &*it : nullptr;
}

std::optional<metrology::GearSense> sense_from_results(const json& results) {
  const json* g = section(results, "gear", json::value_t::object);
  if (!g || !number(*g, "ratio")) return std::nullopt;
  metrology::GearSense sense;
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
  GearSenseFit fit;
  if (!read_samples) {
    // A summary reads the JSON files only.
  } else if (fs::exists(run.samples_path(), ec)) {
    try {
      run.sample_log = count_sample_log(run.samples_path(), fit, run.notes);
    } catch (const std::exception& e) {
      run.notes.push_back(std::string("samples.wbs unreadable: ") + e.what());
    }
  } else {
    run.notes.push_back("no samples.wbs; plots of the raw record are left out");
  }
  if (read_samples)
    run.twin = read_twin_csv_envelope(dir / "twin.csv", kEnvelopeColumns, run.notes);
  run.sense = sense_from_results(run.results);
  if (!run.sense && run.sample_log && run.sample_log->records > 0) {
    run.sense = fit.result();
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

void GearSenseFit::add(const storage::SyncSample& s) {
  if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid)) return;
  const double x = s.theta_out_rad, y = s.theta_in_rad;
  if (n_ == 0) lo_ = hi_ = x;
  lo_ = std::min(lo_, x);
  hi_ = std::max(hi_, x);
  n_ += 1;
  sx_ += x;
  sy_ += y;
  sxx_ += x * x;
  sxy_ += x * y;
}

std::optional<metrology::GearSense> GearSenseFit::result() const {
  // Below about a degree of output travel the TE itself would bend the slope.
  if (n_ < 3 || hi_ - lo_ < 0.02) return std::nullopt;
  const double var = sxx_ - sx_ * sx_ / n_;
  if (!(var > 0)) return std::nullopt;
  const double slope = (sxy_ - sx_ * sy_ / n_) / var;  // s·N
  double ratio = std::abs(slope);
  if (!(ratio > 0) || !std::isfinite(ratio)) return std::nullopt;
  const double half_steps = std::round(ratio * 2) / 2;
  if (std::abs(half_steps - ratio) < 0.01 * ratio) ratio = half_steps;
  metrology::GearSense sense;
  sense.ratio = ratio;
  sense.direction_sign = slope < 0 ? -1 : 1;
  return sense;
}

std::optional<metrology::GearSense> estimate_gear_sense(
    const std::vector<storage::SyncSample>& samples) {
  GearSenseFit fit;
  for (const auto& s : samples) fit.add(s);
  return fit.result();
}

}  // namespace wavebench::report
