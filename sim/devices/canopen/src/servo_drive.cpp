#include "wavebench/simdevices/servo_drive.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "wavebench/simdevices/sdo_abort.hpp"

namespace wavebench::simdevices {
namespace {

constexpr std::uint16_t kNewSetPoint = 0x0010;
constexpr std::uint16_t kChangeImmediately = 0x0020;
constexpr std::uint16_t kRelative = 0x0040;
constexpr std::uint16_t kHalt = 0x0100;

std::int32_t wrap_to_int32(double value) {
  const auto v = static_cast<std::int64_t>(std::llround(value));
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::uint64_t>(v)));
}

// Error register bits (0x1001) for a CiA 402 error code's class.
std::uint8_t error_register_for(std::uint16_t code) {
  std::uint8_t reg = 0x01;  // generic
  switch (code >> 12) {
    case 0x2:
      reg |= 0x02;  // current
      break;
    case 0x3:
      reg |= 0x04;  // voltage
      break;
    case 0x4:
      reg |= 0x08;  // temperature
      break;
    case 0x8:
      reg |= (code >> 8) == 0x81 ? 0x10 : 0x20;  // communication / device profile
      break;
    default:
      break;
  }
  return reg;
}

bool is_position_mode(Cia402Mode m) {
  return m == Cia402Mode::kProfilePosition || m == Cia402Mode::kCyclicSyncPosition;
}

// A window or threshold in object units: at least 1, so that a coarse unit does not close it.
template <typename T>
T window_out(double value) {
  return static_cast<T>(
      std::clamp(std::round(value), 1.0, static_cast<double>(std::numeric_limits<T>::max())));
}

template <typename T>
T unsigned_out(double value) {
  return static_cast<T>(
      std::clamp(std::round(value), 0.0, static_cast<double>(std::numeric_limits<T>::max())));
}

}  // namespace

bool ServoDriveConfig::has(std::uint16_t index) const {
  return std::find(absent_objects.begin(), absent_objects.end(), index) == absent_objects.end();
}

DriveObjectUnits ServoDriveConfig::object_units() const {
  const double cpr = counts_per_revolution;
  switch (velocity_unit) {
    case DriveVelocityUnit::kCounts:
      return {};
    case DriveVelocityUnit::kRpm:
      return {1, 60 / cpr, 60 / cpr};
    case DriveVelocityUnit::kDeciRpm:
      return {1, 600 / cpr, 600 / cpr};
    case DriveVelocityUnit::kFactorGroup:
      break;
  }
  // CiA 402 factor group: position factor = encoder resolution x gear ratio / feed constant
  // converts a user unit into encoder increments (0x608F per motor revolution); likewise the
  // velocity encoder factor with 0x6090. Our increments are counts_per_revolution per motor
  // revolution, so they go to motor revolutions first.
  const auto& f = factor_group;
  const auto ratio = [](std::uint32_t n, std::uint32_t d) {
    return d == 0 ? 0.0 : static_cast<double>(n) / d;
  };
  const double gear = ratio(f.gear_motor_revolutions, f.gear_shaft_revolutions);
  const double feed = ratio(f.feed, f.feed_shaft_revolutions);
  const double pos_res = ratio(f.position_encoder_increments, f.position_encoder_revolutions);
  const double vel_res = ratio(f.velocity_encoder_increments, f.velocity_encoder_revolutions);
  const double position_factor = pos_res * gear / feed;  // 0x608F increments per user unit
  const double velocity_factor = vel_res * gear / feed;  // 0x6090 increments/s per user unit/s
  DriveObjectUnits u;
  u.position = pos_res / cpr / position_factor;
  u.velocity = vel_res / cpr / velocity_factor;
  u.acceleration = u.velocity;
  // A factor group with a zero in it defines no units: the model then runs on increments
  // while its objects show the zero (a master must refuse such a drive).
  if (!(std::isfinite(u.position) && u.position > 0 && std::isfinite(u.velocity) && u.velocity > 0))
    return {};
  return u;
}

std::int32_t Cia402ServoDrive::position_out(double increments) const {
  return wrap_to_int32(increments * units_.position);
}

std::int32_t Cia402ServoDrive::velocity_out(double increments_per_s) const {
  return wrap_to_int32(increments_per_s * units_.velocity);
}

Cia402ServoDrive::Cia402ServoDrive(const ServoDriveConfig& config, FrameSink sink)
    : CanopenNode(config.node_id, config.identity, std::move(sink)),
      config_(config),
      units_(config.object_units()),
      position_loop_(config.position_gain, 0),
      velocity_loop_(config.velocity_gain, config.velocity_integral_time) {
  add_profile_objects();
  set_default_tpdo(1, {{0x6041, 0, 16}, {0x6064, 0, 32}}, true, 1);
  if (config_.has(0x6077)) {
    set_default_tpdo(2, {{0x606C, 0, 32}, {0x6077, 0, 16}}, true, 1);
  } else {
    set_default_tpdo(2, {{0x606C, 0, 32}}, true, 1);
  }
  set_default_rpdo(1, {{0x6040, 0, 16}}, true, 255);
  set_default_rpdo(2, {{0x6040, 0, 16}, {0x607A, 0, 32}}, false, 1);
  set_default_rpdo(3, {{0x6040, 0, 16}, {0x60FF, 0, 32}}, false, 1);
  for (const auto& fixed : config_.fixed_tpdos) fix_tpdo(fixed);
  on_reset_application();
}

void Cia402ServoDrive::add_profile_objects() {
  auto& d = od();
  const auto& c = config_;
  using DT = DataType;
  using A = Access;
  if (c.has(0x603F))
    d.add_value<std::uint16_t>(0x603F, 0, "error code", DT::kUnsigned16, A::kReadOnly, 0, true);
  d.add_value<std::uint16_t>(0x6040, 0, "controlword", DT::kUnsigned16, A::kReadWrite, 0, true)
      .after_write = [this] { on_controlword(); };
  d.add_value<std::uint16_t>(0x6041, 0, "statusword", DT::kUnsigned16, A::kReadOnly, 0, true);
  auto& abort_option =
      d.add_value<std::int16_t>(0x6007, 0, "abort connection option code", DT::kInteger16,
                                A::kReadWrite, c.abort_connection_option);
  abort_option.min = 0;
  abort_option.max = 3;
  auto& qs = d.add_value<std::int16_t>(0x605A, 0, "quick stop option code", DT::kInteger16,
                                       A::kReadWrite, c.quick_stop_option);
  qs.min = 0;
  qs.max = 8;
  auto& mode = d.add_value<std::int8_t>(0x6060, 0, "modes of operation", DT::kInteger8,
                                        A::kReadWrite, 0, true);
  mode.on_write = [](std::span<const std::uint8_t> data) -> std::uint32_t {
    const auto m = static_cast<std::int8_t>(data[0]);
    return (m == 0 || m == 1 || m == 3 || m == 8 || m == 9) ? sdo_abort::kNone
                                                            : sdo_abort::kValueRange;
  };
  mode.after_write = [this] { on_mode_change(); };
  d.add_value<std::int8_t>(0x6061, 0, "modes of operation display", DT::kInteger8, A::kReadOnly, 0,
                           true);
  d.add_value<std::int32_t>(0x6062, 0, "position demand value", DT::kInteger32, A::kReadOnly, 0,
                            true);
  d.add_value<std::int32_t>(0x6064, 0, "position actual value", DT::kInteger32, A::kReadOnly, 0,
                            true);
  d.add_value<std::uint32_t>(
      0x6065, 0, "following error window", DT::kUnsigned32, A::kReadWrite,
      c.following_error_window == 0xFFFFFFFFU
          ? c.following_error_window
          : window_out<std::uint32_t>(c.following_error_window * units_.position));
  d.add_value<std::uint16_t>(0x6066, 0, "following error time out", DT::kUnsigned16, A::kReadWrite,
                             c.following_error_timeout_ms);
  d.add_value<std::uint32_t>(0x6067, 0, "position window", DT::kUnsigned32, A::kReadWrite,
                             window_out<std::uint32_t>(c.position_window * units_.position));
  d.add_value<std::uint16_t>(0x6068, 0, "position window time", DT::kUnsigned16, A::kReadWrite,
                             c.position_window_time_ms);
  d.add_value<std::int32_t>(0x606C, 0, "velocity actual value", DT::kInteger32, A::kReadOnly, 0,
                            true);
  d.add_value<std::uint16_t>(0x606D, 0, "velocity window", DT::kUnsigned16, A::kReadWrite,
                             window_out<std::uint16_t>(c.velocity_window * units_.velocity));
  d.add_value<std::uint16_t>(0x606E, 0, "velocity window time", DT::kUnsigned16, A::kReadWrite,
                             c.velocity_window_time_ms);
  d.add_value<std::uint16_t>(0x606F, 0, "velocity threshold", DT::kUnsigned16, A::kReadWrite,
                             window_out<std::uint16_t>(c.velocity_threshold * units_.velocity));
  d.add_value<std::uint16_t>(0x6072, 0, "max torque", DT::kUnsigned16, A::kReadWrite,
                             c.max_torque_permille, true);
  d.add_value<std::uint32_t>(0x6076, 0, "motor rated torque [mN*m]", DT::kUnsigned32, A::kReadOnly,
                             static_cast<std::uint32_t>(std::lround(c.rated_torque_nm * 1000)));
  if (c.has(0x6077))
    d.add_value<std::int16_t>(0x6077, 0, "torque actual value", DT::kInteger16, A::kReadOnly, 0,
                              true);
  d.add_value<std::int32_t>(0x607A, 0, "target position", DT::kInteger32, A::kReadWrite, 0, true);
  d.add_value<std::uint8_t>(0x607D, 0, "software position limit", DT::kUnsigned8, A::kConst, 2);
  d.add_value<std::int32_t>(0x607D, 1, "min position limit", DT::kInteger32, A::kReadWrite, 0);
  d.add_value<std::int32_t>(0x607D, 2, "max position limit", DT::kInteger32, A::kReadWrite, 0);
  const auto max_speed_inc = unsigned_out<std::uint32_t>(c.max_motor_speed_rpm / 60.0 *
                                                         c.counts_per_revolution * units_.velocity);
  d.add_value<std::uint32_t>(0x607F, 0, "max profile velocity", DT::kUnsigned32, A::kReadWrite,
                             max_speed_inc, true);
  d.add_value<std::uint32_t>(0x6080, 0, "max motor speed [rpm]", DT::kUnsigned32, A::kReadWrite,
                             c.max_motor_speed_rpm);
  d.add_value<std::uint32_t>(0x6081, 0, "profile velocity", DT::kUnsigned32, A::kReadWrite,
                             unsigned_out<std::uint32_t>(c.profile_velocity * units_.velocity),
                             true);
  d.add_value<std::uint32_t>(
      0x6083, 0, "profile acceleration", DT::kUnsigned32, A::kReadWrite,
      unsigned_out<std::uint32_t>(c.profile_acceleration * units_.acceleration), true);
  d.add_value<std::uint32_t>(
      0x6084, 0, "profile deceleration", DT::kUnsigned32, A::kReadWrite,
      unsigned_out<std::uint32_t>(c.profile_deceleration * units_.acceleration), true);
  d.add_value<std::uint32_t>(
      0x6085, 0, "quick stop deceleration", DT::kUnsigned32, A::kReadWrite,
      unsigned_out<std::uint32_t>(c.quick_stop_deceleration * units_.acceleration));
  const bool factor_group = c.velocity_unit == DriveVelocityUnit::kFactorGroup;
  const auto& f = c.factor_group;
  const auto fraction = [&](std::uint16_t index, const char* name, const char* num, std::uint32_t n,
                            const char* den, std::uint32_t dv) {
    d.add_value<std::uint8_t>(index, 0, name, DT::kUnsigned8, A::kConst, 2);
    d.add_value<std::uint32_t>(index, 1, num, DT::kUnsigned32, A::kReadOnly, n);
    d.add_value<std::uint32_t>(index, 2, den, DT::kUnsigned32, A::kReadOnly, dv);
  };
  fraction(0x608F, "position encoder resolution", "encoder increments",
           factor_group ? f.position_encoder_increments : c.counts_per_revolution,
           "motor revolutions", factor_group ? f.position_encoder_revolutions : 1);
  if (factor_group) {
    fraction(0x6090, "velocity encoder resolution", "encoder increments per second",
             f.velocity_encoder_increments, "motor revolutions per second",
             f.velocity_encoder_revolutions);
    fraction(0x6091, "gear ratio", "motor shaft revolutions", f.gear_motor_revolutions,
             "driving shaft revolutions", f.gear_shaft_revolutions);
    fraction(0x6092, "feed constant", "feed", f.feed, "driving shaft revolutions",
             f.feed_shaft_revolutions);
  }
  if (c.si_unit_objects && !factor_group) {
    // Prefix (byte 3), unit (byte 2: 0xB5 increment, 0xB4 revolution), time (byte 1: 0x03 s,
    // 0x47 min).
    const std::uint32_t velocity = c.velocity_unit == DriveVelocityUnit::kRpm       ? 0x00B44700U
                                   : c.velocity_unit == DriveVelocityUnit::kDeciRpm ? 0xFFB44700U
                                                                                    : 0x00B50300U;
    d.add_value<std::uint32_t>(0x60A8, 0, "SI unit position", DT::kUnsigned32, A::kReadOnly,
                               0x00B50000U);
    d.add_value<std::uint32_t>(0x60A9, 0, "SI unit velocity", DT::kUnsigned32, A::kReadOnly,
                               velocity);
  }
  if (c.has(0x60F4))
    d.add_value<std::int32_t>(0x60F4, 0, "following error actual value", DT::kInteger32,
                              A::kReadOnly, 0, true);
  d.add_value<std::int32_t>(0x60FF, 0, "target velocity", DT::kInteger32, A::kReadWrite, 0, true);
  // Supported drive modes: PP (bit 0), PV (bit 2), CSP (bit 7), CSV (bit 8).
  d.add_value<std::uint32_t>(0x6502, 0, "supported drive modes", DT::kUnsigned32, A::kReadOnly,
                             0x00000185U);
  d.add_value<std::uint16_t>(kFaultInjectionIndex, 0, "simulated fault injection", DT::kUnsigned16,
                             A::kWriteOnly, 0)
      .after_write = [this] {
    const auto code = od().get<std::uint16_t>(kFaultInjectionIndex, 0);
    od().set<std::uint16_t>(kFaultInjectionIndex, 0, 0);
    if (code != 0) inject_fault(code);
  };
}

double Cia402ServoDrive::counts_per_radian() const noexcept {
  return config_.counts_per_revolution / (2 * std::numbers::pi);
}

void Cia402ServoDrive::on_reset_application() {
  machine_.reset();
  machine_.power_up();
  active_mode_ = Cia402Mode::kNone;
  last_controlword_ = 0;
  torque_ = 0;
  velocity_loop_.reset();
  limit_active_ = false;
  pp_buffered_ = false;
  set_point_ack_ = false;
  profile_done_ = true;
  target_reached_ = true;
  following_error_ = false;
  following_error_time_ = 0;
  last_sync_ = -1;
  profile_.reset(actual_position_, 0);
  pp_target_ = csp_from_ = csp_to_ = actual_position_;
  od().set<std::uint16_t>(0x6041, 0, statusword());
}

void Cia402ServoDrive::on_nmt_stopped() {
  switch (od().get<std::int16_t>(0x6007, 0)) {
    case 1:
      inject_fault(0x8130);  // life guard / heartbeat error: the communication is gone
      break;
    case 2:
      od().set<std::uint16_t>(0x6040, 0, 0x0000);  // disable voltage
      on_controlword();
      break;
    case 3:
      od().set<std::uint16_t>(0x6040, 0, 0x0002);  // quick stop
      on_controlword();
      break;
    default:
      break;
  }
}

void Cia402ServoDrive::on_mode_change() {
  const auto requested = od().get<std::int8_t>(0x6060, 0);
  active_mode_ = static_cast<Cia402Mode>(requested);
  od().set<std::int8_t>(0x6061, 0, requested);
  // A mode switch is bumpless: the new mode starts from where the shaft is.
  profile_.reset(actual_position_, is_position_mode(active_mode_) ? 0 : actual_velocity_);
  pp_target_ = csp_from_ = csp_to_ = actual_position_;
  profile_done_ = true;
  pp_buffered_ = false;
  csp_elapsed_ = 0;
  od().set<std::uint16_t>(0x6041, 0, statusword());
}

void Cia402ServoDrive::on_controlword() {
  const auto cw = od().get<std::uint16_t>(0x6040, 0);
  const Cia402State before = machine_.state();
  machine_.apply_controlword(cw);
  const Cia402State after = machine_.state();
  if (after != before) {
    if (after == Cia402State::kOperationEnabled && before != Cia402State::kQuickStopActive) {
      profile_.reset(actual_position_, 0);
      pp_target_ = csp_from_ = csp_to_ = actual_position_;
      velocity_loop_.reset();
      profile_done_ = true;
      pp_buffered_ = false;
      target_reached_ = true;
    }
    if (after == Cia402State::kQuickStopActive) profile_.reset(actual_position_, actual_velocity_);
    if (after == Cia402State::kOperationEnabled && before == Cia402State::kQuickStopActive) {
      profile_.reset(actual_position_, 0);
      pp_target_ = actual_position_;
      profile_done_ = true;
    }
    if (before == Cia402State::kFault) {
      if (config_.has(0x603F)) od().set<std::uint16_t>(0x603F, 0, 0);
      following_error_ = false;
      following_error_time_ = 0;
      send_emcy(0x0000, 0x00);  // error reset
    }
  }
  if (after == Cia402State::kOperationEnabled && active_mode_ == Cia402Mode::kProfilePosition) {
    const bool rising = (cw & kNewSetPoint) && !(last_controlword_ & kNewSetPoint);
    const bool falling = !(cw & kNewSetPoint) && (last_controlword_ & kNewSetPoint);
    if (rising) start_new_set_point(cw);
    if (falling && !pp_buffered_) set_point_ack_ = false;
  } else if (!(cw & kNewSetPoint)) {
    set_point_ack_ = false;
  }
  last_controlword_ = cw;
  od().set<std::uint16_t>(0x6041, 0, statusword());
}

void Cia402ServoDrive::start_new_set_point(std::uint16_t cw) {
  const double raw = position_in(od().get<std::int32_t>(0x607A, 0));
  const double target = clamp_to_software_limits((cw & kRelative) ? pp_target_ + raw : raw);
  if (profile_done_ || (cw & kChangeImmediately)) {
    pp_target_ = target;
    profile_done_ = false;
    pp_buffered_ = false;
  } else if (!pp_buffered_) {
    pp_buffered_target_ = target;
    pp_buffered_ = true;
  } else {
    return;  // buffer full: the set-point is not taken, acknowledge stays as it is
  }
  target_reached_ = false;
  in_window_time_ = 0;
  set_point_ack_ = true;
}

double Cia402ServoDrive::clamp_to_software_limits(double position) {
  const auto lo = od().get<std::int32_t>(0x607D, 1);
  const auto hi = od().get<std::int32_t>(0x607D, 2);
  if (lo == 0 && hi == 0) return position;  // limits off
  const double clamped = std::clamp(position, position_in(lo), position_in(hi));
  if (clamped != position) limit_active_ = true;
  return clamped;
}

void Cia402ServoDrive::on_sync(double now) {
  csp_period_ = last_sync_ >= 0 && now > last_sync_ ? now - last_sync_ : 0;
  if (csp_period_ <= 0) {
    const auto us = od().get<std::uint32_t>(0x1006, 0);
    csp_period_ = us != 0 ? us * 1e-6 : 1e-3;
  }
  last_sync_ = now;
  if (active_mode_ == Cia402Mode::kCyclicSyncPosition) {
    csp_from_ = profile_.position();
    csp_to_ = clamp_to_software_limits(position_in(od().get<std::int32_t>(0x607A, 0)));
    csp_elapsed_ = 0;
  }
}

double Cia402ServoDrive::motion_demand(double dt, double& velocity_ff) {
  auto& d = od();
  const double acc = acceleration_in(d.get<std::uint32_t>(0x6083, 0));
  const double dec = acceleration_in(d.get<std::uint32_t>(0x6084, 0));
  const double max_profile = velocity_in(d.get<std::uint32_t>(0x607F, 0));
  const bool halt = d.get<std::uint16_t>(0x6040, 0) & kHalt;

  if (machine_.state() == Cia402State::kQuickStopActive) {
    const auto option = d.get<std::int16_t>(0x605A, 0);
    const double qs_dec =
        (option == 1 || option == 5) ? dec : acceleration_in(d.get<std::uint32_t>(0x6085, 0));
    profile_.step_to_velocity(0, qs_dec, qs_dec, dt);
    if (profile_.velocity() == 0) machine_.quick_stop_done(option >= 0 && option <= 4);
    velocity_ff = profile_.velocity();
    return profile_.position();
  }
  switch (active_mode_) {
    case Cia402Mode::kProfilePosition:
      if (halt) {
        profile_.step_to_velocity(0, acc, dec, dt);
      } else if (!profile_done_) {
        const double v = std::min(velocity_in(d.get<std::uint32_t>(0x6081, 0)), max_profile);
        if (profile_.step_to_position(pp_target_, v, acc, dec, dt)) {
          profile_done_ = true;
          if (pp_buffered_) {
            pp_target_ = pp_buffered_target_;
            pp_buffered_ = false;
            profile_done_ = false;
            if (!(d.get<std::uint16_t>(0x6040, 0) & kNewSetPoint)) set_point_ack_ = false;
          }
        }
      }
      break;
    case Cia402Mode::kProfileVelocity: {
      const double target =
          std::clamp(velocity_in(d.get<std::int32_t>(0x60FF, 0)), -max_profile, max_profile);
      profile_.step_to_velocity(halt ? 0 : target, acc, dec, dt);
      break;
    }
    case Cia402Mode::kCyclicSyncPosition: {
      csp_elapsed_ += dt;
      const double frac = std::min(1.0, csp_elapsed_ / csp_period_);
      const double slope = frac < 1.0 ? (csp_to_ - csp_from_) / csp_period_ : 0.0;
      profile_.reset(csp_from_ + (csp_to_ - csp_from_) * frac, slope);
      break;
    }
    case Cia402Mode::kCyclicSyncVelocity: {
      const double v = velocity_in(d.get<std::int32_t>(0x60FF, 0));
      profile_.reset(profile_.position() + v * dt, v);
      break;
    }
    case Cia402Mode::kNone:
      profile_.step_to_velocity(0, acc, dec, dt);
      break;
  }
  velocity_ff = profile_.velocity();
  return profile_.position();
}

double Cia402ServoDrive::control(const PlantState& plant, double dt) {
  const double cpr = counts_per_radian();
  actual_position_ = plant.theta_in * cpr;
  actual_velocity_ = plant.omega_in * cpr;
  limit_active_ = false;

  if (machine_.state() == Cia402State::kFaultReactionActive) {
    // The fault reaction is to switch the power stage off; the motor coasts.
    machine_.fault_reaction_done();
  }
  if (!machine_.power_stage_on()) {
    torque_ = 0;
    velocity_loop_.reset();
    profile_.reset(actual_position_, 0);
    if (active_mode_ != Cia402Mode::kProfilePosition || profile_done_)
      pp_target_ = actual_position_;
    update_outputs(plant);
    return 0;
  }

  double v_ff = 0;
  const double p_demand = motion_demand(dt, v_ff);
  const bool position_loop = is_position_mode(active_mode_) ||
                             machine_.state() == Cia402State::kQuickStopActive ||
                             active_mode_ == Cia402Mode::kNone;
  const double v_max = od().get<std::uint32_t>(0x6080, 0) / 60.0 * config_.counts_per_revolution;
  const model::PiOutput v_ref =
      position_loop_.evaluate(position_loop ? p_demand - actual_position_ : 0.0, 0, v_max, v_ff);
  const double t_max =
      od().get<std::uint16_t>(0x6072, 0) / 1000.0 * od().get<std::uint32_t>(0x6076, 0) / 1000.0;
  const model::PiOutput torque = velocity_loop_.step(v_ref.value / cpr - plant.omega_in, dt, t_max);
  if (v_ref.limited || torque.limited) limit_active_ = true;
  torque_ = torque.value;

  // Following error supervision in the position modes.
  const double following = p_demand - actual_position_;
  if (config_.has(0x60F4)) od().set<std::int32_t>(0x60F4, 0, position_out(following));
  const auto window = od().get<std::uint32_t>(0x6065, 0);
  if (is_position_mode(active_mode_) && window != 0xFFFFFFFFU &&
      std::abs(following) > position_in(window)) {
    following_error_time_ += dt;
    if (following_error_time_ * 1000 > od().get<std::uint16_t>(0x6066, 0)) {
      following_error_ = true;
      if (config_.following_error_is_fault) inject_fault(0x8611);
    }
  } else {
    following_error_time_ = 0;
    following_error_ = false;
  }
  update_target_reached(actual_position_, actual_velocity_, dt);
  update_outputs(plant);
  return machine_.power_stage_on() ? torque_ : 0.0;
}

void Cia402ServoDrive::update_target_reached(double position, double velocity, double dt) {
  if (machine_.state() != Cia402State::kOperationEnabled) return;
  auto& d = od();
  const bool halt = d.get<std::uint16_t>(0x6040, 0) & kHalt;
  switch (active_mode_) {
    case Cia402Mode::kProfilePosition: {
      if (halt) {
        target_reached_ = profile_.velocity() == 0;
        return;
      }
      const bool inside = profile_done_ && std::abs(pp_target_ - position) <=
                                               position_in(d.get<std::uint32_t>(0x6067, 0));
      in_window_time_ = inside ? in_window_time_ + dt : 0;
      target_reached_ = inside && in_window_time_ * 1000 >= d.get<std::uint16_t>(0x6068, 0);
      return;
    }
    case Cia402Mode::kProfileVelocity: {
      const double target = halt ? 0.0 : velocity_in(d.get<std::int32_t>(0x60FF, 0));
      const bool inside =
          std::abs(velocity - target) <= velocity_in(d.get<std::uint16_t>(0x606D, 0));
      in_window_time_ = inside ? in_window_time_ + dt : 0;
      target_reached_ = inside && in_window_time_ * 1000 >= d.get<std::uint16_t>(0x606E, 0);
      return;
    }
    default:
      target_reached_ = false;
      return;
  }
}

void Cia402ServoDrive::observe(const PlantState& plant) {
  const double cpr = counts_per_radian();
  actual_position_ = plant.theta_in * cpr;
  actual_velocity_ = plant.omega_in * cpr;
  auto& d = od();
  d.set<std::int32_t>(0x6064, 0, position_out(actual_position_));
  d.set<std::int32_t>(0x606C, 0, velocity_out(actual_velocity_));
}

void Cia402ServoDrive::update_outputs(const PlantState& /*plant*/) {
  auto& d = od();
  d.set<std::int32_t>(0x6064, 0, position_out(actual_position_));
  d.set<std::int32_t>(0x606C, 0, velocity_out(actual_velocity_));
  d.set<std::int32_t>(0x6062, 0, position_out(profile_.position()));
  if (config_.has(0x6077)) {
    const double rated = d.get<std::uint32_t>(0x6076, 0) / 1000.0;
    const double permille = std::clamp(std::round(torque_ / rated * 1000), -32768.0, 32767.0);
    d.set<std::int16_t>(0x6077, 0, static_cast<std::int16_t>(permille));
  }
  d.set<std::uint16_t>(0x6041, 0, statusword());
}

std::uint16_t Cia402ServoDrive::mode_bits() const {
  const bool enabled = machine_.state() == Cia402State::kOperationEnabled;
  switch (active_mode_) {
    case Cia402Mode::kProfilePosition:
      return static_cast<std::uint16_t>((set_point_ack_ ? 0x1000 : 0) |
                                        (following_error_ ? 0x2000 : 0));
    case Cia402Mode::kProfileVelocity:
      return std::abs(actual_velocity_) <= velocity_in(od().get<std::uint16_t>(0x606F, 0)) ? 0x1000
                                                                                           : 0;
    case Cia402Mode::kCyclicSyncPosition:
      return static_cast<std::uint16_t>((enabled ? 0x1000 : 0) | (following_error_ ? 0x2000 : 0));
    case Cia402Mode::kCyclicSyncVelocity:
      return enabled ? 0x1000 : 0;
    case Cia402Mode::kNone:
      return 0;
  }
  return 0;
}

std::uint16_t Cia402ServoDrive::statusword() const {
  std::uint16_t sw = machine_.state_bits();
  sw |= 0x0200;  // remote: the controlword is obeyed
  if (target_reached_) sw |= 0x0400;
  if (limit_active_) sw |= 0x0800;
  sw |= mode_bits();
  return sw;
}

void Cia402ServoDrive::inject_fault(std::uint16_t error_code) {
  if (machine_.state() == Cia402State::kFault ||
      machine_.state() == Cia402State::kFaultReactionActive) {
    return;
  }
  if (config_.has(0x603F)) od().set<std::uint16_t>(0x603F, 0, error_code);
  machine_.fault();
  torque_ = 0;
  send_emcy(error_code, error_register_for(error_code));
  od().set<std::uint16_t>(0x6041, 0, statusword());
}

}  // namespace wavebench::simdevices
