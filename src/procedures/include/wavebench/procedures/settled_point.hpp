#pragma once
// One settled position of a static run as it is measured, for a live TE-against-output-angle
// view (what catman's XY view shows while a static run goes on). The same figures as the
// point of results.json's `static` list (static_point_result), in arcsec like the live TE.

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace wavebench::procedures {

struct SettledPoint {
  double output_angle_deg = 0;  // within one output revolution, [0, 360)
  double te_arcsec = 0;
  double load_nm = 0;     // brake torque commanded
  double torque_nm = 0;   // measured, averaged over the window (NaN: no valid torque sample)
  std::string direction;  // "forward" or "reverse"
};

// Called on the bench thread after each position's window: it must return quickly (a short
// lock, no I/O).
// /api/status run.points[] (null for a figure that is not a number).
inline void to_json(nlohmann::json& j, const SettledPoint& p) {
  const auto number = [](double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
  };
  j = {{"output_angle_deg", number(p.output_angle_deg)},
       {"te_arcsec", number(p.te_arcsec)},
       {"load_nm", number(p.load_nm)},
       {"torque_nm", number(p.torque_nm)},
       {"direction", p.direction}};
}

using SettledPointSink = std::function<void(const SettledPoint&)>;

}  // namespace wavebench::procedures
