#include "wavebench/simdevices/bench_plant.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <variant>

#include "wavebench/model/gear_defects.hpp"

namespace wavebench::simdevices {
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

double sign_of(double v) noexcept {
  return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
}

}  // namespace

SimulatedBenchPlant::SimulatedBenchPlant(model::GearParams params, double max_substep)
    : params_(std::move(params)),
      max_substep_(max_substep),
      te_(params_.te_terms),
      dead_zone_(params_.backlash),
      spring_([&]() -> Spring {
        const auto& law = params_.stiffness.law;
        if (const auto* h = std::get_if<model::HystereticBranchStiffness>(&law)) {
          return model::HystereticBranchSpring(*h);
        }
        if (const auto* f = std::get_if<model::FadingMemoryStiffness>(&law)) {
          return model::FadingMemorySpring(*f);
        }
        if (const auto* b = std::get_if<model::BoucWenStiffness>(&law)) {
          return model::BoucWenSpring(*b);
        }
        return model::ElasticStiffness(params_.stiffness);
      }()) {
  const auto& g = params_.geometry;
  ratio_ = g.ratio;
  if (ratio_ == 0 && g.z_circ != g.z_flex) {
    ratio_ = static_cast<double>(g.z_flex) / static_cast<double>(g.z_circ - g.z_flex);
  }
  if (!(ratio_ > 1)) {
    throw std::invalid_argument(
        "gear ratio " + std::to_string(ratio_) +
        " is not usable (expected geometry.ratio or z_flex/z_circ giving N > 1)");
  }
  if (!(params_.inertia_input > 0) || !(params_.inertia_output > 0)) {
    throw std::invalid_argument("inertia_input and inertia_output must be > 0 (got " +
                                std::to_string(params_.inertia_input) + ", " +
                                std::to_string(params_.inertia_output) + ")");
  }
  // The simulated bench's brake is its own device (the Modbus powder-brake controller), set
  // by the procedures: a brake in the unit's case would be a second one nobody drives.
  if (params_.load.brake) {
    throw std::invalid_argument(
        "load.brake: the simulated bench cannot take a brake from the unit's case (expected no "
        "load.brake: the bench's own brake controller loads the output)");
  }
  if (params_.load.output_drag_coulomb != 0 && !(params_.load.drag_smoothing_speed > 0)) {
    throw std::invalid_argument("load.drag_smoothing_speed = " +
                                num(params_.load.drag_smoothing_speed) + " rad/s: expected > 0");
  }
  output_friction_ = params_.friction_side == model::FrictionSide::kOutput;
  const double j_friction = output_friction_ ? params_.inertia_output : params_.inertia_input;
  const std::string shaft = output_friction_ ? "inertia_output" : "inertia_input";
  // The fixed explicit step must resolve the friction law's fastest time constant on its shaft;
  // a sharper law is refused by name rather than run unstable.
  if (const auto* cs = std::get_if<model::CoulombStribeckFriction>(&params_.friction)) {
    friction_ = model::CoulombStribeck(*cs);
    const double slope = std::max(cs->static_torque, cs->coulomb) / cs->smoothing_speed;
    if (max_substep_ * slope / j_friction > 1) {
      throw std::invalid_argument("friction.smoothing_speed = " + num(cs->smoothing_speed) +
                                  " rad/s: too sharp for the simulated bench's step of " +
                                  num(max_substep_) + " s on " + shaft + " (expected >= " +
                                  num(max_substep_ * cs->static_torque / j_friction) + " rad/s)");
    }
  } else if (const auto* lg = std::get_if<model::LuGreFriction>(&params_.friction)) {
    friction_ = model::LuGre(*lg);
    if (max_substep_ * std::sqrt(lg->sigma0 / j_friction) > 1) {
      throw std::invalid_argument(
          "friction.sigma0 = " + num(lg->sigma0) +
          " N*m/rad: too stiff for the simulated bench's step of " + num(max_substep_) + " s on " +
          shaft + " (expected <= " + num(j_friction / (max_substep_ * max_substep_)) + ")");
    }
    if (max_substep_ * (lg->sigma1 + lg->sigma2) / j_friction > 1) {
      throw std::invalid_argument("friction.sigma1 = " + num(lg->sigma1) +
                                  " N*m*s/rad: too much damping for the simulated bench's step "
                                  "of " +
                                  num(max_substep_) + " s on " + shaft + " (expected <= " +
                                  num(j_friction / max_substep_ - lg->sigma2) + ")");
    }
  }
  // Mean stiffness and mesh damping as GearModel derives them (model.md §2).
  double k_small = 0;
  std::visit([&](const auto& spring) { k_small = spring.small_twist_stiffness(); }, spring_);
  const double k_mean = params_.stiffness.mean_stiffness.value_or(k_small);
  if (!(k_mean > 0)) throw std::invalid_argument("stiffness.mean: mean stiffness must be > 0");
  if (params_.damping.coefficient) {
    damping_ = *params_.damping.coefficient;
  } else if (params_.damping.damping_ratio) {
    const double n2j1 = ratio_ * ratio_ * params_.inertia_input;
    const double j_eq = n2j1 * params_.inertia_output / (n2j1 + params_.inertia_output);
    damping_ = 2 * *params_.damping.damping_ratio * std::sqrt(j_eq * k_mean);
  }
  if (!(damping_ >= 0)) {
    throw std::invalid_argument("damping = " + num(damping_) + " N*m*s/rad: expected >= 0");
  }
  // The unit starts at rest, its output where the mesh carries no torque (twist 0), not at
  // θ2 = 0: there the TE offset would preload the spring and the output would ring for the
  // first ~0.1 s of the first run of a new bench, a start no real bench shows. e depends on θ2
  // only through the output orders (a few arcmin per radian), so the fixed point converges in
  // a few steps.
  for (int i = 0; i < 8; ++i) state_.theta_out = -te_excitation(0, state_.theta_out);
  state_.te = state_.theta_out;
}

double SimulatedBenchPlant::te_excitation(double theta_in, double theta_out) const {
  return te_.evaluate(theta_in, theta_out, 0, 0).value;
}

double SimulatedBenchPlant::backlash_filter(double twist) const {
  return dead_zone_.evaluate(twist).x;
}

double SimulatedBenchPlant::stiffness_torque(double x, double theta_in, double theta_out) const {
  switch (spring_.index()) {
    case 0:
      return std::get<0>(spring_).torque(x, theta_in, theta_out);
    case 1:
      return std::get<1>(spring_).torque(x, law_.anchor);
    case 2:
      return std::get<2>(spring_).torque(x, law_.memory);
    default:
      return std::get<3>(spring_).torque(x, law_.memory);
  }
}

double SimulatedBenchPlant::friction_torque(double omega) const {
  if (const auto* cs = std::get_if<model::CoulombStribeck>(&friction_)) return cs->torque(omega);
  if (const auto* lg = std::get_if<model::LuGre>(&friction_)) {
    return lg->evaluate(omega, law_.bristle).torque;
  }
  return 0.0;
}

void SimulatedBenchPlant::step(double dt) {
  if (!(dt > 0)) return;
  const int n = std::max(1, static_cast<int>(std::ceil(dt / max_substep_ - 1e-9)));
  const double h = dt / n;
  for (int i = 0; i < n; ++i) substep(h);
}

void SimulatedBenchPlant::update_branch(double x, double twist_rate, double spring,
                                        bool in_contact) {
  // GearModel locates these events; at a fixed step they are taken at the first step past
  // them, anchored where the torque is then so that it stays continuous.
  if (!in_contact) {
    // Out of contact the element unloads completely; the next contact starts a virgin curve.
    law_.anchor = {0.0, 0.0, true};
    return;
  }
  const double direction = sign_of(twist_rate);
  if (direction != 0 && direction != law_.twist_direction) {
    law_.twist_direction = direction;
    law_.anchor = {x, spring, model::HystereticBranchSpring::loading_after(spring, direction)};
  } else if (!law_.anchor.loading && sign_of(spring) != sign_of(law_.anchor.torque)) {
    // The torque crossed zero while unloading: the element loads again the other way.
    law_.anchor = {x, spring, true};
  }
}

void SimulatedBenchPlant::substep(double h) {
  PlantState& s = state_;
  const double n = ratio_;
  const double j1 = params_.inertia_input;
  const double j2 = params_.inertia_output;

  const model::DefectExcitation defect =
      params_.defects.empty()
          ? model::DefectExcitation{}
          : model::defect_excitation(params_.defects, params_.geometry, s.theta_in, s.theta_out,
                                     s.omega_in, s.omega_out,
                                     s.output_travel_rad / (2 * std::numbers::pi));
  const model::TeValue e = te_.evaluate(s.theta_in, s.theta_out, s.omega_in, s.omega_out);
  const double twist = s.theta_in / n - s.theta_out - e.value - defect.value;
  const double twist_rate = s.omega_in / n - s.omega_out - e.rate - defect.rate;
  const model::DeadZoneValue dz = dead_zone_.evaluate(twist);
  const double x = dz.x;
  const double x_rate = dz.slope * twist_rate;
  const double spring = stiffness_torque(x, s.theta_in, s.theta_out);
  const double damping = damping_ * x_rate;
  // In contact the mesh cannot pull (ElastoBacklash): damping never reverses the torque.
  const double tg = dead_zone_.has_clearance()
                        ? model::limit_backlash_torque(sign_of(x), spring, damping)
                        : spring + damping;

  const double friction_speed = output_friction_ ? s.omega_out : s.omega_in;
  const double friction = friction_torque(friction_speed);

  const auto& load = params_.load;
  const double t_load = load.output_torque.offset +
                        load.output_torque.amplitude *
                            std::sin(2 * std::numbers::pi * load.output_torque.frequency_hz * s.t +
                                     load.output_torque.phase_rad);
  const double ripple = load.drive_ripple.offset +
                        load.drive_ripple.amplitude *
                            std::sin(2 * std::numbers::pi * load.drive_ripple.frequency_hz * s.t +
                                     load.drive_ripple.phase_rad);
  const double drag =
      load.output_drag_coulomb == 0
          ? 0.0
          : load.output_drag_coulomb * std::tanh(s.omega_out / load.drag_smoothing_speed);

  const double input_friction = output_friction_ ? 0.0 : friction;
  const double output_friction = output_friction_ ? friction : 0.0;
  const double acc_in =
      (s.motor_torque + ripple - params_.viscous_input * s.omega_in - input_friction - tg / n) / j1;
  // The brake is a set-valued friction: it holds the output still when the other torques stay
  // within its setting, and slips against the motion otherwise (time-stepping friction).
  const double free_torque =
      tg - params_.viscous_output * s.omega_out - drag - t_load - output_friction;
  const double omega_free = s.omega_out + h * free_torque / j2;
  const double hold = h * brake_limit_ / j2;
  double brake = 0;
  if (std::abs(omega_free) <= hold) {
    brake = -omega_free * j2 / h;
  } else {
    brake = -std::copysign(brake_limit_, omega_free);
  }

  // The laws' own state, forward over the step.
  switch (spring_.index()) {
    case 1:
      update_branch(x, twist_rate, spring, !dead_zone_.has_clearance() || x != 0);
      break;
    case 2:
      law_.memory += h * std::get<2>(spring_).memory_rate(x_rate, law_.memory);
      break;
    case 3:
      law_.memory += h * std::get<3>(spring_).hysteretic_rate(x_rate, law_.memory);
      break;
    default:
      break;
  }
  if (const auto* lg = std::get_if<model::LuGre>(&friction_)) {
    law_.bristle = lg->bristle_after(friction_speed, law_.bristle, h);
  }

  s.omega_in += h * acc_in;
  s.omega_out = std::abs(omega_free) <= hold ? 0.0 : omega_free + h * brake / j2;
  s.theta_in += h * s.omega_in;
  s.theta_out += h * s.omega_out;
  s.output_travel_rad += h * std::abs(s.omega_out);
  s.t += h;
  s.twist = twist;
  s.te = s.theta_out - s.theta_in / n;
  s.gear_torque = tg;
  s.motor_torque = motor_torque_;
  s.brake_torque = brake;
  s.shaft_torque = t_load - brake;
  s.friction_torque = friction;
}

}  // namespace wavebench::simdevices
