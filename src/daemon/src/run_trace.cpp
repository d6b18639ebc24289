#include "wavebench/daemon/run_trace.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "wavebench/analysis/min_max_columns.hpp"
#include "wavebench/model/angle_units.hpp"
#include "wavebench/model/gear_sense.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::daemon {

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
// Records read per page of samples.wbs (about 1.5 MB without extra channels).
constexpr std::size_t kPageRecords = 16384;
// Samples buffered before complete columns are decimated.
constexpr std::size_t kBatchSamples = 65536;
constexpr std::size_t kMaxChannels = 16;

struct BadTraceParameter : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

std::optional<double> seconds_param(const HttpTarget& target, const std::string& key) {
  const auto it = target.query.find(key);
  if (it == target.query.end()) return std::nullopt;
  const auto& text = it->second;
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() ||
      !std::isfinite(value) || value < 0 || value > 1e9) {
    throw BadTraceParameter(key + ": got '" + text +
                            "', expected seconds from the start of the run, 0 to 1e9");
  }
  return value;
}

std::size_t columns_param(const HttpTarget& target) {
  const auto it = target.query.find("columns");
  if (it == target.query.end()) return kDefaultTraceColumns;
  const auto& text = it->second;
  std::size_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || value < 1 ||
      value > kMaxTraceColumns) {
    throw BadTraceParameter("columns: got '" + text + "', expected an integer from 1 to " +
                            std::to_string(kMaxTraceColumns));
  }
  return value;
}

struct Range {
  double from_s = 0, to_s = 0;
};

Range range_params(const HttpTarget& target, double end_s, double start_s = 0) {
  Range r;
  r.from_s = seconds_param(target, "from_s").value_or(start_s);
  r.to_s = seconds_param(target, "to_s").value_or(std::max(end_s, r.from_s));
  if (r.to_s < r.from_s) {
    throw BadTraceParameter("to_s: got '" + target.query.at("to_s") +
                            "', expected at least from_s (" + std::to_string(r.from_s) + ")");
  }
  return r;
}

std::vector<std::string> split_channels(const std::string& text) {
  std::vector<std::string> names;
  std::size_t start = 0;
  while (start <= text.size()) {
    const auto comma = std::min(text.find(',', start), text.size());
    names.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return names;
}

nlohmann::json numbers(const std::vector<double>& values) {
  // NaN (no finite value in a column, a channel that did not arrive) becomes null: a gap.
  nlohmann::json out = nlohmann::json::array();
  for (const double v : values) out.push_back(std::isfinite(v) ? nlohmann::json(v) : nullptr);
  return out;
}

// Min/max per column over a stream of samples, a batch at a time: complete columns of the
// buffer go through analysis::min_max_columns, so the memory held is a batch plus the
// decimated rows however long the range.
class ColumnStream {
 public:
  ColumnStream(double t0, double t1, std::size_t columns, std::size_t series)
      : t0_(t0),
        t1_(t1),
        columns_(columns),
        width_((t1 - t0) / static_cast<double>(columns)),
        values_(series),
        out_values_(series) {}

  // Samples outside [t0, t1] or earlier than the one before are left out.
  void add(double t, std::span<const double> values) {
    if (t < t0_ || t > t1_ || (!t_.empty() && t < t_.back()) || (t < last_flushed_t_)) return;
    ++samples_;
    t_.push_back(t);
    for (std::size_t k = 0; k < values_.size(); ++k) values_[k].push_back(values[k]);
    if (t_.size() >= kBatchSamples && t_.size() > 2 * columns_) flush_complete_columns();
  }

  analysis::DecimatedTrace finish() {
    if (!decimated_) {
      auto all = decimate(t0_, t1_, 0, columns_);
      all.samples_in_range = samples_;
      return all;
    }
    append(decimate_prefix(t_.size(), next_column_, columns_));
    analysis::DecimatedTrace out;
    out.t = std::move(out_t_);
    out.series = std::move(out_values_);
    out.samples_in_range = samples_;
    return out;
  }

 private:
  double column_start(std::size_t c) const {
    return c == columns_ ? t1_ : t0_ + width_ * static_cast<double>(c);
  }

  analysis::DecimatedTrace decimate(double from, double to, std::size_t n, std::size_t columns) {
    const std::size_t count = n == 0 ? t_.size() : n;
    std::vector<std::span<const double>> series;
    for (const auto& v : values_) series.emplace_back(v.data(), count);
    return analysis::min_max_columns(std::span<const double>(t_.data(), count), series, from, to,
                                     columns);
  }

  analysis::DecimatedTrace decimate_prefix(std::size_t n, std::size_t first, std::size_t end) {
    if (n == 0 || end <= first) return {};
    return decimate(column_start(first), column_start(end), n, end - first);
  }

  void append(const analysis::DecimatedTrace& d) {
    if (d.series.size() != out_values_.size()) return;  // nothing decimated
    out_t_.insert(out_t_.end(), d.t.begin(), d.t.end());
    for (std::size_t k = 0; k < out_values_.size(); ++k)
      out_values_[k].insert(out_values_[k].end(), d.series[k].begin(), d.series[k].end());
  }

  void drop_front(std::size_t n) {
    t_.erase(t_.begin(), t_.begin() + static_cast<std::ptrdiff_t>(n));
    for (auto& v : values_) v.erase(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n));
  }

  void flush_complete_columns() {
    decimated_ = true;
    const auto last_column =
        std::min(columns_ - 1, static_cast<std::size_t>(std::max(0.0, (t_.back() - t0_) / width_)));
    if (last_column > next_column_) {
      const double boundary = column_start(last_column);
      const auto n =
          static_cast<std::size_t>(std::lower_bound(t_.begin(), t_.end(), boundary) - t_.begin());
      append(decimate_prefix(n, next_column_, last_column));
      drop_front(n);
      next_column_ = last_column;
      last_flushed_t_ = boundary;
    }
    if (t_.size() >= kBatchSamples) keep_extremes();
  }

  // The buffer lies in one column: only the samples that are some series' min or max there
  // can be drawn, so the others go (in order, so min and max keep their time order).
  void keep_extremes() {
    std::vector<bool> keep(t_.size(), false);
    for (const auto& v : values_) {
      std::optional<std::size_t> lo, hi;
      for (std::size_t i = 0; i < v.size(); ++i) {
        if (!std::isfinite(v[i])) continue;
        if (!lo || v[i] < v[*lo]) lo = i;
        if (!hi || v[i] > v[*hi]) hi = i;
      }
      if (lo) keep[*lo] = keep[*hi] = true;
    }
    keep.back() = true;  // keeps the column's time order for what comes next
    std::size_t w = 0;
    for (std::size_t i = 0; i < t_.size(); ++i) {
      if (!keep[i]) continue;
      t_[w] = t_[i];
      for (auto& v : values_) v[w] = v[i];
      ++w;
    }
    t_.resize(w);
    for (auto& v : values_) v.resize(w);
  }

  double t0_, t1_;
  std::size_t columns_;
  double width_;
  std::vector<double> t_;
  std::vector<std::vector<double>> values_;
  std::vector<double> out_t_;
  std::vector<std::vector<double>> out_values_;
  std::size_t next_column_ = 0;  // first column not yet decimated
  double last_flushed_t_ = -std::numeric_limits<double>::infinity();
  bool decimated_ = false;  // some columns went out decimated: not full resolution
  std::size_t samples_ = 0;
};

nlohmann::json trace_json(const analysis::DecimatedTrace& d,
                          const std::vector<std::string>& names) {
  nlohmann::json series = nlohmann::json::object();
  for (std::size_t k = 0; k < names.size() && k < d.series.size(); ++k)
    series[names[k]] = numbers(d.series[k]);
  return {{"t_s", numbers(d.t)},
          {"series", std::move(series)},
          {"samples_in_range", d.samples_in_range},
          {"full_resolution", d.full_resolution}};
}

// One channel of a sample: TE from the gear sense, or one of the sample's channels (the core
// ones, then the extra ones, as SyncSample::value counts them).
struct Channel {
  std::string name, unit;
  enum class Kind { kSample, kTe } kind = Kind::kSample;
  std::size_t position = 0;  // kSample: the channel's position in the sample
};

std::vector<Channel> known_channels(const std::vector<storage::ChannelInfo>& extra) {
  std::vector<Channel> known{{"te_arcsec", "arcsec", Channel::Kind::kTe, 0}};
  for (std::size_t i = 0; i < storage::kCoreChannels.size(); ++i) {
    const auto& c = storage::kCoreChannels[i];
    known.push_back({std::string(c.name), std::string(c.unit), Channel::Kind::kSample, i});
  }
  for (std::size_t i = 0; i < extra.size() && i < storage::kMaxExtraChannels; ++i)
    known.push_back(
        {extra[i].name, extra[i].unit, Channel::Kind::kSample, storage::kCoreChannelCount + i});
  return known;
}

std::vector<Channel> requested_channels(const HttpTarget& target,
                                        const std::vector<Channel>& known) {
  const auto it = target.query.find("channels");
  const std::string text = it == target.query.end() ? "te_arcsec" : it->second;
  std::string expected;
  for (const auto& c : known) expected += (expected.empty() ? "" : ", ") + c.name;
  std::vector<Channel> out;
  for (const auto& name : split_channels(text)) {
    const auto found =
        std::find_if(known.begin(), known.end(), [&](const Channel& c) { return c.name == name; });
    if (found == known.end()) {
      throw BadTraceParameter("channels: got '" + name + "', expected a comma-separated list of " +
                              expected);
    }
    if (std::none_of(out.begin(), out.end(), [&](const Channel& c) { return c.name == name; }))
      out.push_back(*found);
  }
  if (out.size() > kMaxChannels) {
    throw BadTraceParameter("channels: got " + std::to_string(out.size()) +
                            " names, expected at most " + std::to_string(kMaxChannels));
  }
  return out;
}

double channel_value(const Channel& c, const storage::SyncSample& s,
                     const std::optional<model::GearSense>& sense) {
  switch (c.kind) {
    case Channel::Kind::kSample:
      return s.arrived(c.position) ? s.value(c.position) : kNan;
    case Channel::Kind::kTe:
      if (!sense || !s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid))
        return kNan;
      return sense->transmission_error(s.theta_in_rad, s.theta_out_rad) * model::kArcsecPerRad;
  }
  return kNan;
}

// The gear sense of the run from its results.json, when it has one.
std::optional<model::GearSense> run_gear_sense(const std::filesystem::path& results) {
  std::ifstream in(results);
  if (!in) return std::nullopt;
  const auto j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.contains("gear") || !j["gear"].is_object()) return std::nullopt;
  const auto& g = j["gear"];
  if (!g.contains("ratio") || !g["ratio"].is_number() || !g.contains("direction_sign") ||
      !g["direction_sign"].is_number_integer())
    return std::nullopt;
  model::GearSense sense{g["ratio"].get<double>(), g["direction_sign"].get<int>()};
  if (!(sense.ratio > 0) || (sense.direction_sign != 1 && sense.direction_sign != -1))
    return std::nullopt;
  return sense;
}

std::optional<ApiResponse> unknown_run(const storage::RunStore& store, const std::string& id) {
  if (!store.find_run(id))
    return api_error(404, "not found", "run '" + id + "' is not in the index");
  return std::nullopt;
}

std::int64_t record_time_ns(const std::filesystem::path& path, std::uint64_t index) {
  const auto page = storage::read_sample_log_page(path, index, 1);
  return page.samples.empty() ? 0 : page.samples.front().receive_time_ns;
}

// The first record at or after `t_ns`, by bisection on receive times (one record read per
// step): a zoom into the end of a long run reads only its range.
std::uint64_t first_record_at(const std::filesystem::path& path, std::uint64_t total,
                              std::int64_t t_ns) {
  std::uint64_t lo = 0, hi = total;
  while (lo < hi) {
    const auto mid = lo + (hi - lo) / 2;
    if (record_time_ns(path, mid) < t_ns) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return lo;
}

ApiResponse sample_trace(const storage::RunStore& store, const std::string& id,
                         const HttpTarget& target) {
  if (auto missing = unknown_run(store, id)) return *missing;
  const auto columns = columns_param(target);
  const auto paths = store.paths(id);
  nlohmann::json j = {{"run_id", id}, {"columns", columns}};
  if (!std::filesystem::exists(paths.samples)) {
    // Parameters are still checked: a bad request is a bad request whatever the run holds.
    const auto names = requested_channels(target, known_channels({}));
    const auto range = range_params(target, 0);
    j.update({{"from_s", range.from_s},
              {"to_s", range.to_s},
              {"duration_s", 0},
              {"channels", nlohmann::json::array()},
              {"t_s", nlohmann::json::array()},
              {"series", nlohmann::json::object()},
              {"samples_in_range", 0},
              {"full_resolution", true},
              {"corrupt", false}});
    for (const auto& c : names) {
      j["channels"].push_back({{"name", c.name}, {"unit", c.unit}});
      j["series"][c.name] = nlohmann::json::array();
    }
    return {200, j};
  }
  const auto head = storage::read_sample_log_page(paths.samples, 0, 1);
  const auto channels = requested_channels(target, known_channels(head.header.extra_channels));
  const std::uint64_t total = head.total_records;
  const std::int64_t first_ns = head.samples.empty() ? 0 : head.samples.front().receive_time_ns;
  const std::int64_t last_ns = total == 0 ? first_ns : record_time_ns(paths.samples, total - 1);
  const double duration_s =
      1e-9 * static_cast<double>(std::max<std::int64_t>(0, last_ns - first_ns));
  const auto range = range_params(target, duration_s);

  std::optional<model::GearSense> sense;
  if (std::any_of(channels.begin(), channels.end(),
                  [](const Channel& c) { return c.kind == Channel::Kind::kTe; })) {
    sense = run_gear_sense(paths.results);
    if (!sense) {
      return api_error(409, "conflict",
                       "channels: te_arcsec needs the run's gear (ratio, direction_sign) from its "
                       "results.json, which this run does not have");
    }
  }

  ColumnStream stream(range.from_s, range.to_s, columns, channels.size());
  std::vector<double> values(channels.size());
  bool corrupt = false;
  auto from = first_record_at(paths.samples, total,
                              first_ns + static_cast<std::int64_t>(range.from_s * 1e9));
  const auto to_ns = first_ns + static_cast<std::int64_t>(std::ceil(range.to_s * 1e9));
  for (bool done = false; from < total && !done;) {
    const auto page = storage::read_sample_log_page(paths.samples, from, kPageRecords);
    for (const auto& s : page.samples) {
      if (s.receive_time_ns > to_ns) {
        done = true;
        break;
      }
      for (std::size_t k = 0; k < channels.size(); ++k)
        values[k] = channel_value(channels[k], s, sense);
      stream.add(1e-9 * static_cast<double>(s.receive_time_ns - first_ns), values);
    }
    if (page.corrupt_record) corrupt = true;
    if (page.samples.size() < kPageRecords || page.corrupt_record) break;
    from += page.samples.size();
  }
  const auto decimated = stream.finish();
  std::vector<std::string> names;
  nlohmann::json list = nlohmann::json::array();
  for (const auto& c : channels) {
    names.push_back(c.name);
    list.push_back({{"name", c.name}, {"unit", c.unit}});
  }
  j.update({{"from_s", range.from_s},
            {"to_s", range.to_s},
            {"duration_s", duration_s},
            {"channels", list},
            {"corrupt", corrupt}});
  j.update(trace_json(decimated, names));
  return {200, j};
}

// twin.csv and twin-calibrated.csv (twin_overlay.hpp's write_twin_csv): a header line, then
// t, index, measured, predicted, residual per line; an empty field did not compute.
constexpr const char* kTwinCsvHeader =
    "t,index,measured_te_arcsec,predicted_te_arcsec,residual_arcsec";
const std::vector<std::string> kTwinSeries = {"measured_te_arcsec", "predicted_te_arcsec",
                                              "residual_arcsec"};

double csv_number(std::string_view field) {
  double value = kNan;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  return (field.empty() || ec != std::errc() || end != field.data() + field.size()) ? kNan : value;
}

// The first and the last time of the file, for the default range (reads it once; a line each).
std::optional<std::pair<double, double>> twin_time_span(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line) || line != kTwinCsvHeader) return std::nullopt;
  std::optional<double> first;
  double last = 0;
  while (std::getline(in, line)) {
    const double t = csv_number(std::string_view(line).substr(0, line.find(',')));
    if (!std::isfinite(t)) continue;
    if (!first) first = t;
    last = t;
  }
  if (!first) return std::nullopt;
  return std::make_pair(*first, last);
}

nlohmann::json twin_file_trace(const std::filesystem::path& file, const Range& range,
                               std::size_t columns) {
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line) || line != kTwinCsvHeader) {
    return {{"error", file.filename().string() + ": first line is not '" + kTwinCsvHeader + "'"}};
  }
  ColumnStream stream(range.from_s, range.to_s, columns, kTwinSeries.size());
  std::vector<double> values(kTwinSeries.size());
  std::vector<std::string_view> fields;
  while (std::getline(in, line)) {
    fields.clear();
    std::string_view rest(line);
    for (std::size_t comma; (comma = rest.find(',')) != std::string_view::npos;) {
      fields.push_back(rest.substr(0, comma));
      rest.remove_prefix(comma + 1);
    }
    fields.push_back(rest);
    if (fields.size() != 5) continue;
    const double t = csv_number(fields[0]);
    if (!std::isfinite(t)) continue;
    if (t > range.to_s) break;
    for (std::size_t k = 0; k < values.size(); ++k) values[k] = csv_number(fields[2 + k]);
    stream.add(t, values);
  }
  const auto decimated = stream.finish();
  return trace_json(decimated, kTwinSeries);
}

ApiResponse twin_trace(const storage::RunStore& store, const std::string& id,
                       const HttpTarget& target) {
  if (auto missing = unknown_run(store, id)) return *missing;
  const auto columns = columns_param(target);
  const auto dir = store.paths(id).dir;
  const auto before = dir / "twin.csv";
  const auto after = dir / "twin-calibrated.csv";
  // The twin's times are the bench's (not from the start of the log): the whole range by
  // default is from the first to the last line.
  std::optional<double> start_s;
  double end_s = 0;
  for (const auto& file : {before, after}) {
    if (!std::filesystem::exists(file)) continue;
    if (const auto span = twin_time_span(file)) {
      start_s = std::min(start_s.value_or(span->first), span->first);
      end_s = std::max(end_s, span->second);
    }
  }
  const auto range = range_params(target, end_s, start_s.value_or(0));
  nlohmann::json j = {{"run_id", id},
                      {"columns", columns},
                      {"from_s", range.from_s},
                      {"to_s", range.to_s},
                      {"start_s", start_s.value_or(0)},
                      {"end_s", end_s}};
  j["before"] = std::filesystem::exists(before) ? twin_file_trace(before, range, columns)
                                                : nlohmann::json(nullptr);
  j["after"] = std::filesystem::exists(after) ? twin_file_trace(after, range, columns)
                                              : nlohmann::json(nullptr);
  return {200, j};
}

}  // namespace

ApiResponse run_trace(const storage::RunStore& store, const std::string& id,
                      const HttpTarget& target) {
  try {
    return sample_trace(store, id, target);
  } catch (const BadTraceParameter& e) {
    return api_error(400, "bad request", e.what());
  }
}

ApiResponse run_twin_trace(const storage::RunStore& store, const std::string& id,
                           const HttpTarget& target) {
  try {
    return twin_trace(store, id, target);
  } catch (const BadTraceParameter& e) {
    return api_error(400, "bad request", e.what());
  }
}

}  // namespace wavebench::daemon
