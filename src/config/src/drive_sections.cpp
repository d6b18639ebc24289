// friction, input and load: what drives the gear and what it drives (model.md §2, §6, §7).
#include <string>
#include <utility>

#include "twin_sections.hpp"
#include "wavebench/config/config_error.hpp"

namespace wavebench::config {
namespace {

model::KinematicInput parse_kinematic(YamlSection& s) {
  model::KinematicInput k;
  k.speed = s.quantity_or("speed", Dimension::kAngularSpeed, 0.0);
  s.require_within("speed", k.speed, -kMaxSpeedRadS, kMaxSpeedRadS, "a speed [rad/s]");
  k.ramp_time = s.non_negative_quantity_or("ramp_time", Dimension::kTime, 0.0);
  if (auto trace = s.optional_section("trace")) {
    k.trace_t = trace->quantity_list("t", Dimension::kTime);
    k.trace_theta = trace->quantity_list("theta", Dimension::kAngle);
    if (k.trace_t.size() < 2) trace->fail("t", trace->value_text("t"), "at least two times");
    if (k.trace_theta.size() != k.trace_t.size()) {
      trace->fail("theta", trace->value_text("theta"),
                  std::to_string(k.trace_t.size()) + " angles, one per time");
    }
    for (std::size_t i = 1; i < k.trace_t.size(); ++i) {
      if (!(k.trace_t[i] > k.trace_t[i - 1])) {
        trace->fail("t", trace->value_text("t"), "strictly ascending times");
      }
    }
    trace->finish();
  } else if (!s.has("speed")) {
    s.fail("speed", "", "an input speed such as \"2680 rpm\", or a trace {t, theta}");
  }
  return k;
}

model::DcMotorInput parse_dc_motor(YamlSection& s) {
  model::DcMotorInput m;
  m.resistance = s.positive_quantity("resistance", Dimension::kResistance);
  m.inductance = s.non_negative_quantity_or("inductance", Dimension::kInductance, 0.0);
  m.torque_constant = s.positive_quantity("torque_constant", Dimension::kTorqueConstant);
  m.back_emf_constant =
      s.non_negative_quantity_or("back_emf_constant", Dimension::kBackEmfConstant, -1.0);
  if (m.back_emf_constant < 0) s.fail("back_emf_constant", "", "a back-EMF constant (required)");
  m.no_load_torque = s.non_negative_quantity_or("no_load_torque", Dimension::kTorque, 0.0);
  if (!s.has("voltage")) s.fail("voltage", "", "the supply voltage (required)");
  m.voltage = sinusoid_or(s, "voltage", Dimension::kVoltage);
  return m;
}

model::ServoDriveInput parse_servo(YamlSection& s) {
  model::ServoDriveInput d;
  d.position_control = s.boolean_or("position_control", false);
  d.position_gain = s.non_negative_quantity_or("position_gain", Dimension::kRate, 0.0);
  d.velocity_gain = s.positive_quantity("velocity_gain", Dimension::kDamping);
  d.velocity_integral_time =
      s.non_negative_quantity_or("velocity_integral_time", Dimension::kTime, 0.0);
  d.torque_limit = s.non_negative_quantity_or("torque_limit", Dimension::kTorque, 0.0);
  d.speed_limit = s.non_negative_quantity_or("speed_limit", Dimension::kAngularSpeed, 0.0);
  d.speed_setpoint = s.quantity_or("speed_setpoint", Dimension::kAngularSpeed, 0.0);
  s.require_within("speed_setpoint", d.speed_setpoint, -kMaxSpeedRadS, kMaxSpeedRadS,
                   "a speed [rad/s]");
  d.position_setpoint = s.quantity_or("position_setpoint", Dimension::kAngle, 0.0);
  if (d.position_control && !(d.position_gain > 0)) {
    s.fail("position_gain", s.value_text("position_gain"),
           "a gain > 0 when position_control is on");
  }
  return d;
}

}  // namespace

void parse_friction_section(YamlSection& s, model::FrictionLaw& friction,
                            model::FrictionSide& side) {
  const std::string law = s.choice("model", {"none", "coulomb_stribeck", "lugre"});
  if (const auto at = s.optional_choice("side", {"input", "output"})) {
    side = *at == "output" ? model::FrictionSide::kOutput : model::FrictionSide::kInput;
  }
  if (law == "coulomb_stribeck") {
    model::CoulombStribeckFriction f;
    f.coulomb = s.non_negative_quantity_or("coulomb", Dimension::kTorque, 0.0);
    f.static_torque = s.non_negative_quantity_or("static", Dimension::kTorque, f.coulomb);
    f.stribeck_speed = s.positive_quantity("stribeck_speed", Dimension::kAngularSpeed);
    f.viscous = s.non_negative_quantity_or("viscous", Dimension::kDamping, 0.0);
    f.smoothing_speed =
        s.non_negative_quantity_or("smoothing_speed", Dimension::kAngularSpeed, 1e-4);
    friction = f;
  } else if (law == "lugre") {
    model::LuGreFriction f;
    f.sigma0 = s.positive_quantity("sigma0", Dimension::kStiffness);
    f.sigma1 = s.non_negative_quantity_or("sigma1", Dimension::kDamping, 0.0);
    f.sigma2 = s.non_negative_quantity_or("sigma2", Dimension::kDamping, 0.0);
    f.coulomb = s.positive_quantity("coulomb", Dimension::kTorque);
    f.static_torque = s.non_negative_quantity_or("static", Dimension::kTorque, f.coulomb);
    f.stribeck_speed = s.positive_quantity("stribeck_speed", Dimension::kAngularSpeed);
    if (f.static_torque < f.coulomb) {
      s.fail("static", s.value_text("static"),
             "a static torque >= the Coulomb torque " + s.value_text("coulomb"));
    }
    friction = f;
  } else {
    friction = model::NoFriction{};
  }
  s.finish();
}

void parse_input_section(YamlSection& s, model::GearParams& gear) {
  const std::string type = s.choice("type", {"torque", "dc_motor", "servo", "kinematic"});
  double nominal = 0.0;
  if (type == "torque") {
    model::TorqueInput t;
    if (!s.has("torque")) s.fail("torque", "", "the input torque (required)");
    t.torque = sinusoid_or(s, "torque", Dimension::kTorque);
    gear.input = t;
  } else if (type == "dc_motor") {
    gear.input = parse_dc_motor(s);
  } else if (type == "servo") {
    const auto d = parse_servo(s);
    nominal = d.position_control ? 0.0 : d.speed_setpoint;
    gear.input = d;
  } else {
    const auto k = parse_kinematic(s);
    nominal = k.trace_t.empty() ? k.speed : 0.0;
    gear.input = k;
  }
  // The reference motion of the deviation coordinates; an explicit value wins.
  gear.nominal_input_speed = s.quantity_or("nominal_speed", Dimension::kAngularSpeed, nominal);
  s.require_within("nominal_speed", gear.nominal_input_speed, -kMaxSpeedRadS, kMaxSpeedRadS,
                   "a speed [rad/s]");
  s.finish();
}

void parse_load_section(YamlSection& s, model::LoadParams& load) {
  load.output_torque = sinusoid_or(s, "output_torque", Dimension::kTorque);
  load.drive_ripple = sinusoid_or(s, "drive_ripple", Dimension::kTorque);
  load.output_drag_coulomb = s.non_negative_quantity_or("output_drag", Dimension::kTorque, 0.0);
  load.drag_smoothing_speed =
      s.non_negative_quantity_or("drag_smoothing_speed", Dimension::kAngularSpeed, 1e-3);
  if (auto b = s.optional_section("brake")) {
    // Keys of the brake description before it was one with the simulated bench's (issue #9):
    // their meaning changed, so they are refused naming what replaced them.
    static const std::pair<const char*, const char*> kReplaced[] = {
        {"torque_per_amp",
         "rated_torque (T = rated_torque * I / rated_current above "
         "threshold_current)"},
        {"falling_ratio", "hysteresis (a current: the falling curve is T(I + hysteresis))"},
        {"time_constant", "tau_rise and tau_fall"},
        {"holding_speed", "standstill_speed"},
    };
    for (const auto& [old_key, replacement] : kReplaced) {
      if (b->has(old_key)) {
        b->fail(old_key, b->value_text(old_key),
                std::string("no longer a key: give ") + replacement);
      }
    }
    const auto positive_or = [&](const char* key, Dimension dimension, double fallback) {
      const double v = b->non_negative_quantity_or(key, dimension, fallback);
      if (!(v > 0)) b->fail(key, b->value_text(key), describe(dimension) + " > 0");
      return v;
    };
    model::PowderBrakeParams p;
    p.rated_current_a = b->positive_quantity("rated_current", Dimension::kCurrent);
    p.rated_torque_nm = b->positive_quantity("rated_torque", Dimension::kTorque);
    p.threshold_current_a =
        b->non_negative_quantity_or("threshold_current", Dimension::kCurrent, 0);
    p.hysteresis_a = b->non_negative_quantity_or("hysteresis", Dimension::kCurrent, 0);
    p.tau_rise_s = positive_or("tau_rise", Dimension::kTime, 0.05);
    p.tau_fall_s = positive_or("tau_fall", Dimension::kTime, p.tau_rise_s);
    load.brake_current_a = b->non_negative_quantity_or("current", Dimension::kCurrent, 0.0);
    p.standstill_rad_per_s = positive_or("standstill_speed", Dimension::kAngularSpeed, 1e-3);
    // Bounds that keep the twin's integration finite: a lag far below the integrator's step, or
    // a hysteresis wider than the whole current range, is a typo, not a brake.
    b->require_within("tau_rise", p.tau_rise_s, 1e-4, 100, "a lag time constant in s");
    b->require_within("tau_fall", p.tau_fall_s, 1e-4, 100, "a lag time constant in s");
    b->require_within("standstill_speed", p.standstill_rad_per_s, 1e-9, 10,
                      "a standstill speed in rad/s");
    p.heat_capacity_j_per_k =
        b->non_negative_quantity_or("thermal_capacity", Dimension::kHeatCapacity, 0);
    const double resistance =
        b->non_negative_quantity_or("thermal_resistance", Dimension::kThermalResistance, 0);
    if (p.heat_capacity_j_per_k > 0 && !(resistance > 0)) {
      b->fail("thermal_resistance", b->value_text("thermal_resistance"),
              "a thermal resistance > 0 K/W with a thermal_capacity");
    }
    p.heat_loss_w_per_k = resistance > 0 ? 1 / resistance : 0;
    p.ambient_c = b->quantity_or("ambient_temperature", Dimension::kTemperature, 25.0);
    b->require_within("hysteresis", p.hysteresis_a, 0, p.rated_current_a,
                      "a hysteresis width in A, at most rated_current");
    if (p.rated_current_a <= p.threshold_current_a) {
      b->fail("rated_current", b->value_text("rated_current"),
              "a current above threshold_current " + b->value_text("threshold_current"));
    }
    b->finish();
    load.brake = p;
  }
  s.finish();
}

}  // namespace wavebench::config
