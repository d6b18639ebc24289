#include "wavebench/bench/safety_limits_check.hpp"

#include <cmath>
#include <sstream>

namespace wavebench::bench {
namespace {

std::string crossed(const char* what, double value, double limit, const char* unit,
                    double scale = 1) {
  std::ostringstream out;
  out.precision(4);
  out << what << " " << value * scale << " " << unit << " beyond the limit " << limit * scale << " "
      << unit;
  return out.str();
}

bool over(double limit, double value) {
  return limit > 0 && std::abs(value) > limit;
}

}  // namespace

std::optional<std::string> SafetyLimitsCheck::check(const storage::SyncSample& s,
                                                    const DriveCycleValues& drive,
                                                    std::optional<double> coil_temperature_c) {
  using storage::SampleFlag;
  const auto& l = limits_;
  if (s.valid(storage::kInputSpeedValid) && over(l.max_input_speed_rad_s, s.input_speed_rad_s))
    return crossed("input speed", s.input_speed_rad_s, l.max_input_speed_rad_s, "rpm",
                   60 / (2 * M_PI));
  if (s.valid(storage::kThetaOutValid)) {
    const auto speed = encoder_speed_.add(s.receive_time_ns, s.theta_out_rad);
    if (speed && over(l.max_input_speed_rad_s, *speed))
      return crossed("input speed measured by the output encoder × ratio", *speed,
                     l.max_input_speed_rad_s, "rpm", 60 / (2 * M_PI));
  }
  if (s.valid(storage::kBrakeCurrentValid) && over(l.max_brake_current_a, s.brake_current_a))
    return crossed("brake current", s.brake_current_a, l.max_brake_current_a, "A");
  if (s.valid(storage::kBrakeTorqueValid) && over(l.max_brake_torque_nm, s.brake_torque_nm))
    return crossed("brake torque", s.brake_torque_nm, l.max_brake_torque_nm, "N*m");
  if (s.valid(storage::kTorqueValid) && over(l.max_measured_torque_nm, s.torque_nm))
    return crossed("measured torque", s.torque_nm, l.max_measured_torque_nm, "N*m");
  if (drive.following_error_valid && over(l.max_following_error_rad, drive.following_error_rad))
    return crossed("following error", drive.following_error_rad, l.max_following_error_rad,
                   "rad (input)");
  if (coil_temperature_c && l.max_coil_temperature_c > 0 &&
      *coil_temperature_c > l.max_coil_temperature_c)
    return crossed("brake coil temperature", *coil_temperature_c, l.max_coil_temperature_c, "degC");
  if (s.valid(storage::kThetaInValid) && s.valid(storage::kThetaOutValid)) {
    const double te = sense_.transmission_error(s.theta_in_rad, s.theta_out_rad);
    if (!have_te0_) {
      te0_ = te;
      have_te0_ = true;
    } else if (over(l.max_te_excursion_rad, te - te0_)) {
      return crossed("TE excursion", te - te0_, l.max_te_excursion_rad, "arcmin",
                     model::kArcminPerRad);
    }
  }
  return std::nullopt;
}

}  // namespace wavebench::bench
