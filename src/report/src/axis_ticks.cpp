#include "wavebench/report/axis_ticks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace wavebench::report {
namespace {

double nice_step(double span, int max_ticks) {
  const double raw = span / std::max(1, max_ticks - 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    if (m * mag >= raw) return m * mag;
  }
  return 10 * mag;
}

}  // namespace

AxisRange nice_range(double lo, double hi, int max_ticks) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) return {0, 1};
  if (lo > hi) std::swap(lo, hi);
  if (hi - lo <= 1e-300 || hi - lo <= 1e-12 * std::max(std::abs(lo), std::abs(hi))) {
    const double pad = lo == 0 ? 1.0 : std::abs(lo) * 0.1;
    lo -= pad;
    hi += pad;
  }
  const double step = nice_step(hi - lo, max_ticks);
  return {std::floor(lo / step) * step, std::ceil(hi / step) * step};
}

std::vector<double> nice_ticks(double lo, double hi, int max_ticks) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  const double step = nice_step(hi - lo, max_ticks);
  const double first = std::ceil(lo / step - 1e-9) * step;
  for (double t = first; t <= hi + step * 1e-9; t += step) {
    ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
    if (ticks.size() > 100) break;
  }
  return ticks;
}

std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> ticks;
  if (!(lo > 0) || !(hi > lo)) return ticks;
  const int d0 = static_cast<int>(std::floor(std::log10(lo)));
  const int d1 = static_cast<int>(std::ceil(std::log10(hi)));
  const int decades = d1 - d0;
  const int every = std::max(1, decades / 8);  // thin out long ranges
  for (int d = d0; d <= d1; ++d) {
    const double base = std::pow(10.0, d);
    if ((d - d0) % every == 0 && base >= lo * (1 - 1e-9) && base <= hi * (1 + 1e-9)) {
      ticks.push_back(base);
    }
    if (decades <= 2) {
      for (const double m : {2.0, 5.0}) {
        const double t = m * base;
        if (t >= lo && t <= hi) ticks.push_back(t);
      }
    }
  }
  std::sort(ticks.begin(), ticks.end());
  return ticks;
}

std::string tick_label(double value, double spacing) {
  char buf[32];
  const double a = std::abs(value);
  if (value != 0 && (a >= 1e5 || a < 1e-3)) {
    std::snprintf(buf, sizeof buf, "%.3g", value);
    return buf;
  }
  // Enough decimals for the spacing itself (2.5 needs one, 0.25 two), none beyond.
  int decimals = 0;
  if (spacing > 0) {
    while (decimals < 6) {
      const double scaled = spacing * std::pow(10.0, decimals);
      if (std::abs(scaled - std::round(scaled)) < 1e-6 * std::max(1.0, scaled)) break;
      ++decimals;
    }
  }
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value == 0 ? 0.0 : value);
  return buf;
}

}  // namespace wavebench::report
