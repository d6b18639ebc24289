#include "wavebench/daemon/live_stream.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>

#include "wavebench/analysis/min_max_columns.hpp"
#include "wavebench/model/gear_sense.hpp"

namespace wavebench::daemon {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::size_t kMaxSamplesPerFrame = 65536;
// The sample's channels the live plots draw beside TE (series 1..3), keyed by their columns.
constexpr std::array<std::size_t, 3> kPlotted{
    storage::channel::kInputSpeed, storage::channel::kTorque, storage::channel::kBrakeCurrent};

template <typename T>
T number_param(const HttpTarget& target, const std::string& key, T fallback, T low, T high,
               const char* kind) {
  const auto it = target.query.find(key);
  if (it == target.query.end()) return fallback;
  const auto& text = it->second;
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() ||
      !(value >= low && value <= high)) {
    throw std::invalid_argument(key + ": got '" + text + "', expected " + kind + " from " +
                                std::to_string(low) + " to " + std::to_string(high));
  }
  return value;
}

double te_arcsec(double theta_in, double theta_out, double ratio, int sign) {
  return model::GearSense{ratio, sign}.transmission_error(theta_in, theta_out) *
         model::kArcsecPerRad;
}

// NaN (no valid value in a column) as null: JSON has no NaN.
nlohmann::json values_json(const std::vector<double>& values) {
  nlohmann::json out = nlohmann::json::array();
  for (const double v : values)
    out.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr));
  return out;
}

}  // namespace

LiveStreamParams live_stream_params(const HttpTarget& target) {
  LiveStreamParams p;
  p.window_s = number_param<double>(target, "window_s", p.window_s, LiveStreamParams::kMinWindowS,
                                    LiveStreamParams::kMaxWindowS, "a number of seconds");
  p.columns = number_param<std::size_t>(target, "columns", p.columns, LiveStreamParams::kMinColumns,
                                        LiveStreamParams::kMaxColumns, "an integer");
  for (const auto& [key, value] : target.query) {
    if (key != "window_s" && key != "columns") {
      throw std::invalid_argument(key + ": unknown parameter; expected window_s or columns");
    }
  }
  return p;
}

LiveStreamFrames::LiveStreamFrames(const LiveSampleBuffer& live,
                                   std::function<nlohmann::json()> status, LiveStreamParams params,
                                   std::shared_ptr<void> slot)
    : live_(live), status_(std::move(status)), params_(params), slot_(std::move(slot)) {}

void LiveStreamFrames::take_sense(const nlohmann::json& status) {
  const auto bench = status.find("bench");
  if (bench == status.end() || !bench->is_object()) return;
  const double ratio = bench->value("ratio", 0.0);
  if (ratio > 0) ratio_ = ratio;
  direction_sign_ = bench->value("direction_sign", 1) < 0 ? -1 : 1;
}

nlohmann::json LiveStreamFrames::frame() {
  nlohmann::json j = nlohmann::json::object();
  if (frames_++ % kStatusEvery == 0) {
    auto status = status_();
    take_sense(status);
    j["status"] = std::move(status);
  }
  const auto slice = live_.since(next_seq_, kMaxSamplesPerFrame);
  next_seq_ = slice.next_seq;
  bool reset = false;
  for (const auto& live : slice.samples) {
    const auto& s = live.sample;
    const double t = static_cast<double>(s.receive_time_ns) * 1e-9;
    if (!t_.empty() && t < t_.back()) {  // a new time base: what is pending belongs to the old
      reset = true;
      t_.clear();
      for (auto& v : series_) v.clear();
    }
    const bool angles = s.valid(storage::kThetaInValid) && s.valid(storage::kThetaOutValid);
    t_.push_back(t);
    series_[0].push_back(angles && ratio_
                             ? te_arcsec(s.theta_in_rad, s.theta_out_rad, *ratio_, direction_sign_)
                             : kNaN);
    for (std::size_t k = 0; k < kPlotted.size(); ++k)
      series_[k + 1].push_back(s.arrived(kPlotted[k]) ? s.value(kPlotted[k]) : kNaN);
  }
  const double width = params_.window_s / static_cast<double>(params_.columns);
  if (!t_.empty()) {
    // Columns before the one holding the newest sample are complete.
    const auto end_column = static_cast<long long>(std::floor(t_.back() / width));
    auto first_column = static_cast<long long>(std::floor(t_.front() / width));
    // After a long pause only the last window matters.
    first_column = std::max(first_column, end_column - static_cast<long long>(params_.columns));
    std::size_t n = 0;
    while (n < t_.size() && t_[n] < static_cast<double>(end_column) * width) ++n;
    if (n > 0 && end_column > first_column) {
      std::vector<std::span<const double>> spans;
      for (const auto& v : series_) spans.emplace_back(v.data(), n);
      const auto rows = analysis::min_max_columns(
          std::span<const double>(t_.data(), n), spans, static_cast<double>(first_column) * width,
          static_cast<double>(end_column) * width,
          static_cast<std::size_t>(end_column - first_column));
      j["rows"] = {{"t", rows.t}, {"te_arcsec", values_json(rows.series[0])}};
      for (std::size_t k = 0; k < kPlotted.size(); ++k)
        j["rows"][std::string(storage::kCoreChannels[kPlotted[k]].column)] =
            values_json(rows.series[k + 1]);
      j["full_resolution"] = rows.full_resolution;
      t_.erase(t_.begin(), t_.begin() + static_cast<std::ptrdiff_t>(n));
      for (auto& v : series_) v.erase(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n));
    }
  }
  if (j.empty() && slice.missed == 0 && !reset) return nullptr;
  j["seq"] = next_seq_;
  j["missed"] = slice.missed;
  j["column_s"] = width;
  j["reset"] = reset;
  return j;
}

std::optional<std::string> LiveStreamFrames::next() {
  const auto j = frame();
  if (j.is_null()) return std::string();
  return "data: " + j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n\n";
}

}  // namespace wavebench::daemon
