#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "wavebench/report/run_plots.hpp"
#include "wavebench/report/sample_log_scan.hpp"

namespace wavebench::report {
namespace {

// Cells of the grid a long curve is binned in: about 2 px each on the 1400 x 800 figure.
constexpr std::size_t kGridX = 640, kGridY = 360;

struct Point {
  double twist_arcmin = 0, torque_nm = 0;
  int travel = 1;
};

// As torque_twist_from_samples: twist θ1/N − θ2 = −TE, the torque's sign the direction of
// travel (a brake only resists motion).
template <class Visit>
void scan_points(const std::filesystem::path& log, std::uint64_t records,
                 const metrology::GearSense& sense, Visit&& visit) {
  scan_sample_log(log, 0, records, [&](const storage::SyncSample& s) {
    if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid) ||
        !s.valid(storage::kTorqueValid)) {
      return;
    }
    visit(Point{
        -sense.transmission_error(s.theta_in_rad, s.theta_out_rad) * metrology::kArcminPerRad,
        s.torque_nm, s.torque_nm < 0 ? -1 : 1});
  });
}

}  // namespace

std::optional<TorqueTwistCurve> torque_twist_from_log(const std::filesystem::path& log,
                                                      std::uint64_t records,
                                                      const metrology::GearSense& sense) {
  std::size_t n = 0;
  double x_lo = 0, x_hi = 0, y_lo = 0, y_hi = 0;
  scan_points(log, records, sense, [&](const Point& p) {
    x_lo = n == 0 ? p.twist_arcmin : std::min(x_lo, p.twist_arcmin);
    x_hi = n == 0 ? p.twist_arcmin : std::max(x_hi, p.twist_arcmin);
    y_lo = n == 0 ? p.torque_nm : std::min(y_lo, p.torque_nm);
    y_hi = n == 0 ? p.torque_nm : std::max(y_hi, p.torque_nm);
    ++n;
  });
  if (n < 8) return std::nullopt;
  TorqueTwistCurve c;
  const auto keep = [&c](const Point& p) {
    c.twist_arcmin.push_back(p.twist_arcmin);
    c.torque_nm.push_back(p.torque_nm);
    c.travel.push_back(p.travel);
  };
  if (n <= kTorqueTwistPoints) {
    scan_points(log, records, sense, keep);
  } else {
    std::vector<bool> occupied(2 * kGridX * kGridY, false);
    const auto cell = [](double v, double lo, double hi, std::size_t cells) {
      if (!(hi > lo) || !std::isfinite(v)) return std::size_t{0};
      const double f = std::floor((v - lo) / (hi - lo) * static_cast<double>(cells));
      return static_cast<std::size_t>(std::clamp(f, 0.0, static_cast<double>(cells - 1)));
    };
    scan_points(log, records, sense, [&](const Point& p) {
      const std::size_t k = (p.travel > 0 ? 0 : kGridX * kGridY) +
                            cell(p.twist_arcmin, x_lo, x_hi, kGridX) * kGridY +
                            cell(p.torque_nm, y_lo, y_hi, kGridY);
      if (occupied[k]) return;
      occupied[k] = true;
      keep(p);
    });
  }
  c.twist_label = n <= kTorqueTwistPoints
                      ? "twist (-TE at the output, every sample) [arcmin]"
                      : "twist (-TE at the output, a point per occupied cell of " +
                            std::to_string(n) + " samples) [arcmin]";
  c.from_samples = true;
  return c;
}

}  // namespace wavebench::report
