#include "wavebench/twin/twin_overlay.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "wavebench/procedures/gear_sense.hpp"
#include "wavebench/storage/atomic_file.hpp"

namespace wavebench::twin {

TwinOverlay twin_overlay(std::span<const TwinPoint> points) {
  TwinOverlay o;
  for (const auto& p : points) {
    if (!std::isfinite(p.measured_te_rad) || !std::isfinite(p.predicted_te_rad)) continue;
    o.index.push_back(p.index);
    o.t_s.push_back(p.t_s);
    o.measured_te_rad.push_back(p.measured_te_rad);
    o.predicted_te_rad.push_back(p.predicted_te_rad);
  }
  return o;
}

procedures::TwinResidual twin_overlay_residual(const TwinOverlay& overlay,
                                               analysis::SpectrumAnalyser& analyser,
                                               analysis::Window window) {
  return procedures::twin_residual(overlay.t_s, overlay.measured_te_rad, overlay.predicted_te_rad,
                                   window, analyser);
}

void write_twin_csv(const std::filesystem::path& file, std::span<const TwinPoint> points) {
  std::string text = "t,index,measured_te_arcsec,predicted_te_arcsec,residual_arcsec\n";
  text.reserve(text.size() + points.size() * 64);
  char buf[160];
  auto field = [&](double rad) {
    if (!std::isfinite(rad)) return std::string();
    std::snprintf(buf, sizeof buf, "%.4f", rad * procedures::kArcsecPerRad);
    return std::string(buf);
  };
  for (const auto& p : points) {
    std::snprintf(buf, sizeof buf, "%.6f,%llu,", p.t_s, static_cast<unsigned long long>(p.index));
    text += buf;
    text += field(p.measured_te_rad);
    text += ',';
    text += field(p.predicted_te_rad);
    text += ',';
    text += field(p.measured_te_rad - p.predicted_te_rad);
    text += '\n';
  }
  storage::write_file_atomically(file, text);
}

}  // namespace wavebench::twin
