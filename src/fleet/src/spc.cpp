#include "wavebench/fleet/spc.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wavebench::fleet {

SpcFigures spc_figures(const std::vector<double>& values, const SpecLimits& limits) {
  if (values.size() < 2) {
    throw std::invalid_argument("spc: " + std::to_string(values.size()) +
                                " values, expected at least 2 (a moving range needs two)");
  }
  if (limits.lower && limits.upper && *limits.lower >= *limits.upper) {
    throw std::invalid_argument("spc: lower limit " + std::to_string(*limits.lower) +
                                " is not below upper limit " + std::to_string(*limits.upper));
  }
  SpcFigures s;
  s.n = values.size();
  const double n = static_cast<double>(s.n);
  double sum = 0;
  for (double v : values) sum += v;
  s.mean = sum / n;
  double squares = 0;
  for (double v : values) squares += (v - s.mean) * (v - s.mean);
  s.sigma = std::sqrt(squares / (n - 1));
  double ranges = 0;
  for (std::size_t i = 1; i < values.size(); ++i) ranges += std::abs(values[i] - values[i - 1]);
  s.mr_bar = ranges / (n - 1);
  s.sigma_within = s.mr_bar / kD2;
  s.ucl = s.mean + kIndividualsFactor * s.mr_bar;
  s.lcl = s.mean - kIndividualsFactor * s.mr_bar;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] > s.ucl || values[i] < s.lcl) s.out_of_control.push_back(i);
  }
  // Capability: a side without a limit gives nothing; a zero sigma gives no index (infinite).
  const auto indices = [&](double sigma, std::optional<double>& c, std::optional<double>& ck) {
    if (!(sigma > 0)) return;
    if (limits.lower && limits.upper) c = (*limits.upper - *limits.lower) / (6 * sigma);
    std::optional<double> upper, lower;
    if (limits.upper) upper = (*limits.upper - s.mean) / (3 * sigma);
    if (limits.lower) lower = (s.mean - *limits.lower) / (3 * sigma);
    if (upper && lower) {
      ck = std::min(*upper, *lower);
    } else if (upper) {
      ck = upper;
    } else if (lower) {
      ck = lower;
    }
  };
  indices(s.sigma_within, s.cp, s.cpk);
  indices(s.sigma, s.pp, s.ppk);
  return s;
}

nlohmann::json to_json(const SpcFigures& s) {
  const auto opt = [](const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  return {{"n", s.n},
          {"mean", s.mean},
          {"sigma", s.sigma},
          {"mr_bar", s.mr_bar},
          {"sigma_within", s.sigma_within},
          {"ucl", s.ucl},
          {"lcl", s.lcl},
          {"cp", opt(s.cp)},
          {"cpk", opt(s.cpk)},
          {"pp", opt(s.pp)},
          {"ppk", opt(s.ppk)},
          {"out_of_control", s.out_of_control}};
}

}  // namespace wavebench::fleet
