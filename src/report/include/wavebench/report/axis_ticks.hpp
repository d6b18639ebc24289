#pragma once
// Tick positions people read easily: 1, 2, 5 times a power of ten on linear axes, decades
// (with 2 and 5 between when few) on logarithmic ones.

#include <string>
#include <vector>

namespace wavebench::report {

struct AxisRange {
  double lo = 0, hi = 1;
};

// Widens [lo, hi] to tick multiples; handles lo == hi and non-finite input.
AxisRange nice_range(double lo, double hi, int max_ticks = 8);
std::vector<double> nice_ticks(double lo, double hi, int max_ticks = 8);
// Ticks inside [lo, hi] (lo > 0) for a log axis.
std::vector<double> log_ticks(double lo, double hi);
// A tick label with as many decimals as the spacing needs ("0.25", "1e+04").
std::string tick_label(double value, double spacing);

}  // namespace wavebench::report
