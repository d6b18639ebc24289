#include "wavebench/report/timeseries_csv.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace wavebench::report {
namespace {

model::SampledResponse two_samples() {
  model::SampledResponse r;
  r.t = {0.0, 1e-4};
  for (auto* ch : {&r.theta1, &r.omega1, &r.theta2_dev, &r.omega2, &r.alpha2, &r.twist,
                   &r.twist_rate, &r.gear_torque, &r.load_torque, &r.motor_torque}) {
    *ch = {0.1, 0.2};
  }
  r.te = {std::numbers::pi / 180 / 3600, -2 * std::numbers::pi / 180 / 3600};  // 1, -2 arcsec
  return r;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

TEST(TimeseriesCsv, HeaderRowsAndArcsecColumns) {
  std::ostringstream out;
  write_timeseries_csv(out, two_samples());
  std::istringstream in(out.str());
  std::string header, row1, row2, extra;
  std::getline(in, header);
  std::getline(in, row1);
  std::getline(in, row2);
  EXPECT_FALSE(std::getline(in, extra));
  const auto names = split(header);
  EXPECT_EQ(names, timeseries_columns());
  ASSERT_EQ(names.front(), "t_s");
  const auto cells = split(row2);
  ASSERT_EQ(cells.size(), names.size());
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == "te_arcsec") {
      EXPECT_NEAR(std::stod(cells[i]), -2.0, 1e-12);
    }
    if (names[i] == "te_rad") {
      EXPECT_DOUBLE_EQ(std::stod(cells[i]), two_samples().te[1]);
    }
    if (names[i] == "t_s") {
      EXPECT_DOUBLE_EQ(std::stod(cells[i]), 1e-4);
    }
    if (names[i] == "twist_arcsec") {
      EXPECT_NEAR(std::stod(cells[i]), 0.2 * 206264.806, 1e-3);
    }
  }
}

TEST(TimeseriesCsv, ValuesRoundTripExactly) {
  model::SampledResponse r = two_samples();
  r.omega2 = {1.0 / 3.0, std::nextafter(1.0, 2.0)};
  std::ostringstream out;
  write_timeseries_csv(out, r);
  std::istringstream in(out.str());
  std::string header, row;
  std::getline(in, header);
  const auto names = split(header);
  std::getline(in, row);
  std::getline(in, row);
  const auto cells = split(row);
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == "omega2_rad_s") {
      EXPECT_EQ(std::stod(cells[i]), std::nextafter(1.0, 2.0));
    }
  }
}

TEST(TimeseriesCsv, MissingChannelLeavesEmptyCellsNotShiftedColumns) {
  model::SampledResponse r = two_samples();
  r.motor_torque.clear();
  std::ostringstream out;
  write_timeseries_csv(out, r);
  std::istringstream in(out.str());
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(split(row).size(), split(header).size());
}

}  // namespace
}  // namespace wavebench::report
