#include "wavebench/report/timeseries_csv.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <numbers>
#include <stdexcept>

#include "wavebench/model/angle_units.hpp"

namespace wavebench::report {
namespace {

struct Column {
  const char* name;
  const std::vector<double> model::SampledResponse::*channel;
  double scale;
};

const Column kColumns[] = {
    {"t_s", &model::SampledResponse::t, 1},
    {"theta1_rad", &model::SampledResponse::theta1, 1},
    {"omega1_rad_s", &model::SampledResponse::omega1, 1},
    {"theta2_dev_rad", &model::SampledResponse::theta2_dev, 1},
    {"theta2_dev_arcsec", &model::SampledResponse::theta2_dev, model::kArcsecPerRad},
    {"omega2_rad_s", &model::SampledResponse::omega2, 1},
    {"alpha2_rad_s2", &model::SampledResponse::alpha2, 1},
    {"twist_rad", &model::SampledResponse::twist, 1},
    {"twist_arcsec", &model::SampledResponse::twist, model::kArcsecPerRad},
    {"twist_rate_rad_s", &model::SampledResponse::twist_rate, 1},
    {"te_rad", &model::SampledResponse::te, 1},
    {"te_arcsec", &model::SampledResponse::te, model::kArcsecPerRad},
    {"gear_torque_nm", &model::SampledResponse::gear_torque, 1},
    {"load_torque_nm", &model::SampledResponse::load_torque, 1},
    {"motor_torque_nm", &model::SampledResponse::motor_torque, 1},
};

}  // namespace

std::vector<std::string> timeseries_columns() {
  std::vector<std::string> names;
  for (const auto& c : kColumns) names.emplace_back(c.name);
  return names;
}

void write_timeseries_csv(std::ostream& out, const model::SampledResponse& response) {
  bool first = true;
  for (const auto& c : kColumns) {
    out << (first ? "" : ",") << c.name;
    first = false;
  }
  out << '\n';
  const std::size_t rows = response.t.size();
  std::string line;
  char buf[40];
  for (std::size_t i = 0; i < rows; ++i) {
    line.clear();
    bool first_column = true;
    for (const auto& c : kColumns) {
      if (!first_column) line += ',';
      first_column = false;
      const auto& v = response.*(c.channel);
      // A channel the model did not fill stays empty rather than shifting the columns.
      if (i >= v.size()) continue;
      // Shortest round-trip text: the file reads back to the same doubles.
      const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v[i] * c.scale);
      if (ec == std::errc()) line.append(buf, end);
    }
    line += '\n';
    out << line;
  }
}

void write_timeseries_csv(const std::filesystem::path& path,
                          const model::SampledResponse& response) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path.string());
  write_timeseries_csv(out, response);
  out.flush();
  if (!out) throw std::runtime_error("error while writing " + path.string());
}

}  // namespace wavebench::report
