#include "wavebench/twin/twin_overlay.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "wavebench/metrology/gear_sense.hpp"

namespace wavebench::twin {

void TwinOverlaySum::add(const TwinPoint& p) {
  if (!std::isfinite(p.measured_te_rad) || !std::isfinite(p.predicted_te_rad)) {
    // A point without both breaks the run of consecutive samples as a gap does.
    seen_ = 0;
    return;
  }
  residual_.add(p.measured_te_rad, p.predicted_te_rad);
  ++overlapping_;
  for (std::size_t i = 0; i + 1 < 4; ++i) {
    index_[i] = index_[i + 1];
    value_[i] = value_[i + 1];
  }
  index_[3] = p.index;
  value_[3] = p.measured_te_rad - p.predicted_te_rad;
  seen_ = std::min<std::size_t>(seen_ + 1, 4);
  if (seen_ == 4 && index_[3] == index_[0] + 3) {
    const double d = -value_[0] + 3 * value_[1] - 3 * value_[2] + value_[3];
    third_squares_ += d * d;
    ++thirds_;
  }
}

double TwinOverlaySum::noise_floor_arcsec() const {
  return thirds_ == 0 ? 0.0
                      : std::sqrt(third_squares_ / (20.0 * static_cast<double>(thirds_))) *
                            metrology::kArcsecPerRad;
}

metrology::TwinResidual twin_overlay_residual(std::span<const TwinPoint> points) {
  TwinOverlaySum sum;
  for (const auto& p : points) sum.add(p);
  return sum.residual();
}

TwinCsvWriter::TwinCsvWriter(const std::filesystem::path& file) : file_(file) {
  file_.append("t,index,measured_te_arcsec,predicted_te_arcsec,residual_arcsec\n");
}

void TwinCsvWriter::add(const TwinPoint& p) {
  char row[256];
  int n = std::snprintf(row, 64, std::abs(p.t_s) < 1e12 ? "%.6f,%llu," : "%.6e,%llu,", p.t_s,
                        static_cast<unsigned long long>(p.index));
  const auto field = [&](double rad, char end) {
    const double arcsec = rad * metrology::kArcsecPerRad;
    if (std::isfinite(arcsec)) {
      // %.4f of a value beyond 1e12 would not fit the row: such a value is written in %e.
      n += std::snprintf(row + n, 48, std::abs(arcsec) < 1e12 ? "%.4f" : "%.6e", arcsec);
    }
    row[n++] = end;
  };
  field(p.measured_te_rad, ',');
  field(p.predicted_te_rad, ',');
  field(p.measured_te_rad - p.predicted_te_rad, '\n');
  file_.append(std::string_view(row, static_cast<std::size_t>(n)));
  ++rows_;
}

void TwinCsvWriter::commit() {
  file_.commit();
}

void write_twin_csv(const std::filesystem::path& file, std::span<const TwinPoint> points) {
  TwinCsvWriter writer(file);
  for (const auto& p : points) writer.add(p);
  writer.commit();
}

}  // namespace wavebench::twin
