#include "wavebench/model/gear_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "wavebench/model/angle_units.hpp"
#include "wavebench/model/sinusoid.hpp"

namespace wavebench::model {
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

double resolve_ratio(const GearGeometry& g) {
  double from_teeth = 0;
  if (g.z_flex > 0 && g.z_circ > g.z_flex) {
    from_teeth = static_cast<double>(g.z_flex) / static_cast<double>(g.z_circ - g.z_flex);
  }
  if (g.ratio > 0) {
    if (from_teeth > 0 && std::abs(from_teeth - g.ratio) > 1e-9 * g.ratio) {
      throw std::invalid_argument("geometry.ratio = " + num(g.ratio) + ": expected " +
                                  num(from_teeth) + " from z_flex = " + std::to_string(g.z_flex) +
                                  " and z_circ = " + std::to_string(g.z_circ));
    }
    return g.ratio;
  }
  if (from_teeth > 0) return from_teeth;
  throw std::invalid_argument("geometry.ratio = " + num(g.ratio) +
                              ": expected > 0 (or z_circ > z_flex > 0)");
}

}  // namespace

GearModel::GearModel(const GearParams& params, bool locate_events)
    : params_(params),
      te_(params.te_terms),
      dead_zone_(params.backlash),
      spring_([&]() -> Spring {
        const auto& law = params.stiffness.law;
        if (const auto* h = std::get_if<HystereticBranchStiffness>(&law)) {
          return HystereticBranchSpring(*h);
        }
        if (const auto* f = std::get_if<FadingMemoryStiffness>(&law)) {
          return FadingMemorySpring(*f);
        }
        if (const auto* b = std::get_if<BoucWenStiffness>(&law)) return BoucWenSpring(*b);
        return ElasticStiffness(params.stiffness);
      }()),
      drive_([&]() -> Drive {
        const auto& in = params.input;
        if (const auto* m = std::get_if<DcMotorInput>(&in)) return DcMotor(*m);
        if (const auto* s = std::get_if<ServoDriveInput>(&in)) return ServoDrive(*s);
        if (const auto* k = std::get_if<KinematicInput>(&in)) return KinematicMotion(*k);
        return TorqueDrive{std::get<TorqueInput>(in).torque};
      }()) {
  ratio_ = resolve_ratio(params.geometry);
  inv_ratio_ = 1.0 / ratio_;
  j1_ = params.inertia_input;
  j2_ = params.inertia_output;
  kinematic_ = std::holds_alternative<KinematicMotion>(drive_);
  if (!(j2_ > 0)) {
    throw std::invalid_argument("inertia_output = " + num(j2_) + " kg*m^2: expected > 0");
  }
  if (!params.defects.empty()) {
    // A twin that modelled the defect would predict it, and so never flag it.
    throw std::invalid_argument(
        "defects: only the simulated bench's unit takes them (expected a gear without a "
        "defects section for the model and the twin)");
  }
  if (!(j1_ > 0) && !(kinematic_ && j1_ == 0)) {
    throw std::invalid_argument("inertia_input = " + num(j1_) +
                                " kg*m^2: expected > 0 (0 only with a kinematic input)");
  }
  omega_ref_ = kinematic_ ? 0.0 : params.nominal_input_speed;
  if (const auto* cs = std::get_if<CoulombStribeckFriction>(&params.friction)) {
    friction_ = CoulombStribeck(*cs);
  } else if (const auto* lg = std::get_if<LuGreFriction>(&params.friction)) {
    friction_ = LuGre(*lg);
  }
  if (params.load.brake) brake_.emplace(*params.load.brake, params.load.brake_current_a);
  if (params.load.output_drag_coulomb != 0 && !(params.load.drag_smoothing_speed > 0)) {
    throw std::invalid_argument("load.drag_smoothing_speed = " +
                                num(params.load.drag_smoothing_speed) + " rad/s: expected > 0");
  }

  // Mean stiffness and mesh damping (model.md §2).
  double k_small = 0;
  std::visit([&](const auto& s) { k_small = s.small_twist_stiffness(); }, spring_);
  mean_stiffness_ = params.stiffness.mean_stiffness.value_or(k_small);
  j_eq_ = j1_ > 0 ? ratio_ * ratio_ * j1_ * j2_ / (ratio_ * ratio_ * j1_ + j2_) : j2_;
  if (params.damping.coefficient) {
    damping_ = *params.damping.coefficient;
  } else if (params.damping.damping_ratio) {
    damping_ = 2.0 * *params.damping.damping_ratio * std::sqrt(j_eq_ * mean_stiffness_);
  }
  if (!(damping_ >= 0)) {
    throw std::invalid_argument("damping = " + num(damping_) + " N*m*s/rad: expected >= 0");
  }

  // Fastest excitation at the nominal input speed, for the error scales.
  double nominal_speed = params.nominal_input_speed;
  if (const auto* k = std::get_if<KinematicInput>(&params.input)) {
    nominal_speed = k->speed;
    if (k->trace_t.size() >= 2) {
      nominal_speed = (k->trace_theta.back() - k->trace_theta.front()) /
                      (k->trace_t.back() - k->trace_t.front());
    }
  }
  auto line = [&](double a, double b) { return std::abs((a + b * inv_ratio_) * nominal_speed); };
  for (const auto& t : params.te_terms) {
    fastest_line_ = std::max(fastest_line_, line(t.order_input, t.order_output));
  }
  for (const auto& h : params.stiffness.modulation) {
    fastest_line_ = std::max(fastest_line_, line(h.order_input, h.order_output));
  }
  if (const auto* l = std::get_if<LinearPeriodicStiffness>(&params.stiffness.law)) {
    for (const auto& h : l->harmonics) {
      fastest_line_ = std::max(fastest_line_, line(h.order_input, h.order_output));
    }
  }

  // State layout.
  int n = 0;
  auto next = [&n] { return n++; };
  if (!kinematic_) {
    layout_.input_angle = next();
    layout_.input_speed = next();
  }
  layout_.twist = next();
  layout_.twist_rate = next();
  if (const auto* m = std::get_if<DcMotor>(&drive_); m && m->has_current_state()) {
    layout_.motor_current = next();
  }
  if (const auto* s = std::get_if<ServoDrive>(&drive_); s && s->has_integral_state()) {
    layout_.speed_integral = next();
  }
  if (std::holds_alternative<LuGre>(friction_)) layout_.bristle = next();
  if (std::holds_alternative<FadingMemorySpring>(spring_)) layout_.memory = next();
  if (std::holds_alternative<BoucWenSpring>(spring_)) layout_.bouc_wen = next();
  if (brake_) {
    layout_.brake_capacity = next();
    if (brake_->has_thermal_state()) layout_.brake_temperature = next();
  }
  layout_.dissipated_energy = next();
  layout_.size = static_cast<std::size_t>(n);

  int w = 0;
  const bool branches = std::holds_alternative<HystereticBranchSpring>(spring_);
  if (branches) {
    layout_.anchor_twist = 0;
    layout_.anchor_torque = 1;
    layout_.anchor_loading = 2;
    layout_.twist_direction = 3;
    layout_.discrete_size = 4;
  }
  if (locate_events && dead_zone_.is_sharp() && dead_zone_.half_width() > 0) {
    layout_.witness_upper_flank = w++;
    layout_.witness_lower_flank = w++;
  }
  // The branch switches are the model's own discrete dynamics, located whatever the option.
  if (branches) {
    layout_.witness_reversal = w++;
    layout_.witness_zero_torque = w++;
  }
  layout_.witness_count = static_cast<std::size_t>(w);
}

GearModel::MeshMotion GearModel::mesh_motion(double t, const double* y) const noexcept {
  const StateLayout& L = layout_;
  MeshMotion m;
  if (kinematic_) {
    const InputMotion in = std::get<KinematicMotion>(drive_).at(t);
    m.theta1 = in.theta;
    m.omega1 = in.omega;
    m.alpha1 = in.alpha;
  } else {
    m.u1 = y[L.input_angle];
    m.theta1 = omega_ref_ * t + m.u1;
    m.omega1 = omega_ref_ + y[L.input_speed];
  }
  m.q = y[L.twist];
  m.r = y[L.twist_rate];
  m.theta2 = m.theta1 * inv_ratio_ - m.q;
  m.omega2 = m.omega1 * inv_ratio_ - m.r;
  m.e = te_.evaluate(m.theta1, m.theta2, m.omega1, m.omega2);
  m.delta = m.q - m.e.value;
  m.delta_rate = m.r - m.e.rate;
  return m;
}

void GearModel::evaluate(double t, const double* y, const double* d, double* dydt,
                         GearOutputs* out) const {
  const StateLayout& L = layout_;
  const MeshMotion m = mesh_motion(t, y);
  const double theta1 = m.theta1, omega1 = m.omega1, u1 = m.u1, q = m.q, r = m.r;
  const double theta2 = m.theta2, omega2 = m.omega2, delta = m.delta, delta_rate = m.delta_rate;
  const TeValue e = m.e;
  double alpha1 = m.alpha1;

  // Mesh: dead zone, spring, damping.
  const DeadZoneValue dz = dead_zone_.evaluate(delta);
  const double x = dz.x;
  const double x_rate = dz.slope * delta_rate;
  double spring = 0, hysteresis_loss = 0;
  switch (spring_.index()) {
    case 0:
      spring = std::get<0>(spring_).torque(x, theta1, theta2);
      break;
    case 1: {
      const BranchAnchor a{d[L.anchor_twist], d[L.anchor_torque], d[L.anchor_loading] > 0.5};
      spring = std::get<1>(spring_).torque(x, a);
      hysteresis_loss = spring * x_rate;  // work into the element; the loop area per cycle
      break;
    }
    case 2: {
      const auto& s = std::get<2>(spring_);
      const double z = y[L.memory];
      spring = s.torque(x, z);
      hysteresis_loss = s.dissipation(z);
      if (dydt) dydt[L.memory] = s.memory_rate(x_rate, z);
      break;
    }
    default: {
      const auto& s = std::get<3>(spring_);
      const double wb = y[L.bouc_wen];
      spring = s.torque(x, wb);
      hysteresis_loss = s.dissipation(x_rate, wb);
      if (dydt) dydt[L.bouc_wen] = s.hysteretic_rate(x_rate, wb);
      break;
    }
  }
  const double damping = damping_ * x_rate;
  const double gear =
      dead_zone_.has_clearance()
          ? limit_backlash_torque(x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0), spring, damping)
          : spring + damping;

  // Friction at the wave generator or at the output bearing.
  const bool output_friction = params_.friction_side == FrictionSide::kOutput;
  const double friction_speed = output_friction ? omega2 : omega1;
  double friction = 0, friction_loss = 0;
  if (const auto* cs = std::get_if<CoulombStribeck>(&friction_)) {
    friction = cs->torque(friction_speed);
    friction_loss = friction * friction_speed;
  } else if (const auto* lg = std::get_if<LuGre>(&friction_)) {
    const LuGreState st = lg->evaluate(friction_speed, y[L.bristle]);
    friction = st.torque;
    friction_loss = st.dissipation;
    if (dydt) dydt[L.bristle] = st.bristle_rate;
  }
  const double input_friction = output_friction ? 0.0 : friction;

  // Load on the output.
  const LoadParams& lp = params_.load;
  double load = model::evaluate(lp.output_torque, t);
  double drag = 0;
  if (lp.output_drag_coulomb != 0) {
    drag = lp.output_drag_coulomb * std::tanh(omega2 / lp.drag_smoothing_speed);
    load += drag;
  }
  if (output_friction) load += friction;
  if (brake_) {
    const double capacity = y[L.brake_capacity];
    const double brake = brake_->torque(capacity, omega2);
    load += brake;
    if (dydt) {
      dydt[L.brake_capacity] = brake_->capacity_rate(capacity);
      if (L.brake_temperature >= 0) {
        dydt[L.brake_temperature] =
            brake_->temperature_rate(y[L.brake_temperature], brake * omega2);
      }
    }
  }

  // Input torque and accelerations.
  const double cj = params_.viscous_input;
  const double cz = params_.viscous_output;
  const double omega2_dot = (gear - cz * omega2 - load) / j2_;
  double motor = 0;
  if (kinematic_) {
    motor = j1_ * alpha1 + cj * omega1 + input_friction + gear * inv_ratio_;
  } else {
    const double ripple = model::evaluate(lp.drive_ripple, t);
    switch (drive_.index()) {
      case 0:
        motor = model::evaluate(std::get<0>(drive_).torque, t);
        break;
      case 1: {
        const auto& dc = std::get<1>(drive_);
        if (L.motor_current >= 0) {
          const double i = y[L.motor_current];
          motor = dc.torque(i);
          if (dydt) dydt[L.motor_current] = dc.current_rate(t, i, omega1);
        } else {
          motor = dc.torque(dc.algebraic_current(t, omega1));
        }
        break;
      }
      default: {
        const ServoOutput s = std::get<2>(drive_).evaluate(
            theta1, omega1, L.speed_integral >= 0 ? y[L.speed_integral] : 0.0);
        motor = s.torque;
        if (dydt && L.speed_integral >= 0) dydt[L.speed_integral] = s.integral_rate;
        break;
      }
    }
    motor += ripple;
    alpha1 = (motor - cj * omega1 - input_friction - gear * inv_ratio_) / j1_;
  }

  const double loss = (gear - spring) * delta_rate + hysteresis_loss + friction_loss +
                      cj * omega1 * omega1 + cz * omega2 * omega2 + drag * omega2;
  if (dydt) {
    if (!kinematic_) {
      dydt[L.input_angle] = y[L.input_speed];
      dydt[L.input_speed] = alpha1;
    }
    dydt[L.twist] = r;
    dydt[L.twist_rate] = alpha1 * inv_ratio_ - omega2_dot;
    dydt[L.dissipated_energy] = loss;
  }
  if (out) {
    out->theta1 = theta1;
    out->omega1 = omega1;
    out->alpha1 = alpha1;
    out->theta2_dev = kinematic_ ? -q : u1 * inv_ratio_ - q;
    out->omega2 = omega2;
    out->alpha2 = omega2_dot;
    out->te_excitation = e.value;
    out->te_excitation_rate = e.rate;
    out->twist = delta;
    out->twist_rate = delta_rate;
    out->spring_twist = x;
    out->te = -q;
    out->spring_torque = spring;
    out->gear_torque = gear;
    out->load_torque = load;
    out->motor_torque = motor;
    out->friction_torque = friction;
    out->loss_power = loss;
  }
}

void GearModel::derivatives(double t, std::span<const double> y, std::span<const double> d,
                            std::span<double> dydt) const {
  evaluate(t, y.data(), d.data(), dydt.data(), nullptr);
}

GearOutputs GearModel::outputs(double t, std::span<const double> y,
                               std::span<const double> d) const {
  GearOutputs o;
  evaluate(t, y.data(), d.data(), nullptr, &o);
  return o;
}

double GearModel::preload_twist(double torque) const {
  const auto* el = std::get_if<ElasticStiffness>(&spring_);
  if (!el || torque == 0.0) return 0.0;
  // The curve is odd and monotone: bracket, then bisect.
  const double target = std::abs(torque);
  double lo = 0, hi = target / std::max(mean_stiffness_, 1e-300);
  for (int i = 0; i < 200 && el->torque_unmodulated(hi) < target; ++i) hi *= 2;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (el->torque_unmodulated(mid) < target ? lo : hi) = mid;
  }
  const double x = 0.5 * (lo + hi);
  return torque < 0 ? -x : x;
}

std::vector<double> GearModel::initial_state() const {
  std::vector<double> y(layout_.size, 0.0);
  const StateLayout& L = layout_;
  double theta1 = 0, omega1 = omega_ref_;
  if (kinematic_) {
    const InputMotion m = std::get<KinematicMotion>(drive_).at(0.0);
    theta1 = m.theta;
    omega1 = m.omega;
  }
  const double omega2 = omega1 * inv_ratio_;
  const LoadParams& lp = params_.load;
  double mean_load = lp.output_torque.offset + params_.viscous_output * omega2;
  if (lp.output_drag_coulomb != 0) {
    mean_load += lp.output_drag_coulomb * std::tanh(omega2 / lp.drag_smoothing_speed);
  }
  const double x = preload_twist(mean_load);
  const double delta = x == 0 ? 0.0 : x + (x > 0 ? 1.0 : -1.0) * dead_zone_.half_width();
  // q = Delta + e(theta1, theta1/N - q) and r = e': a few fixed-point passes (|e| << 1 rad).
  double q = delta, r = 0;
  for (int i = 0; i < 4; ++i) {
    const TeValue e = te_.evaluate(theta1, theta1 * inv_ratio_ - q, omega1, omega2 - r);
    q = delta + e.value;
    r = e.rate;
  }
  y[L.twist] = q;
  y[L.twist_rate] = r;
  if (L.brake_temperature >= 0) y[L.brake_temperature] = brake_->params().ambient_c;
  if (L.motor_current >= 0) {
    y[L.motor_current] = std::get<DcMotor>(drive_).algebraic_current(0.0, omega1);
  }
  return y;
}

std::vector<double> GearModel::initial_discrete() const {
  std::vector<double> d(layout_.discrete_size, 0.0);
  if (layout_.anchor_loading >= 0) {
    d[layout_.anchor_loading] = 1.0;
    d[layout_.twist_direction] = 1.0;
  }
  return d;
}

void GearModel::error_scale(std::span<double> scale) const {
  const StateLayout& L = layout_;
  // Angles: the larger of an arcsecond, the clearance and the static twist. Rates: that angle
  // at the fastest motion the model has, its mesh resonance or its fastest excitation line at
  // the nominal speed. atol acts on these near the zero crossings of an oscillating rate;
  // any smaller and the step size collapses there without the lines getting more accurate.
  const auto y0 = initial_state();
  const double angle = std::max({kRadPerArcsec, dead_zone_.half_width(), std::abs(y0[L.twist])});
  const double omega_n = std::max(
      fastest_line_, j_eq_ > 0 && mean_stiffness_ > 0 ? std::sqrt(mean_stiffness_ / j_eq_) : 1.0);
  std::fill(scale.begin(), scale.end(), 1.0);
  if (L.input_angle >= 0) {
    scale[L.input_angle] = ratio_ * angle;
    scale[L.input_speed] = ratio_ * angle * omega_n;
  }
  scale[L.twist] = angle;
  scale[L.twist_rate] = angle * omega_n;
  if (L.bristle >= 0) scale[L.bristle] = std::get<LuGre>(friction_).steady_deflection();
  if (L.memory >= 0) scale[L.memory] = std::max(1e-12, mean_stiffness_ * angle);
  if (L.bouc_wen >= 0) scale[L.bouc_wen] = angle;
  if (L.speed_integral >= 0) scale[L.speed_integral] = ratio_ * angle;
  if (L.motor_current >= 0) scale[L.motor_current] = 1e-3;
  if (L.brake_capacity >= 0) scale[L.brake_capacity] = 1e-3;
  scale[L.dissipated_energy] = 1e-6;
}

void GearModel::witnesses(double t, std::span<const double> y, std::span<const double> d,
                          std::span<double> g) const {
  const StateLayout& L = layout_;
  // Called after every step: only the form-5 witnesses need the full model.
  GearOutputs o;
  if (L.witness_reversal >= 0) {
    evaluate(t, y.data(), d.data(), nullptr, &o);
  } else {
    const MeshMotion m = mesh_motion(t, y.data());
    o.twist = m.delta;
  }
  if (L.witness_upper_flank >= 0) {
    g[static_cast<std::size_t>(L.witness_upper_flank)] = o.twist - dead_zone_.half_width();
    g[static_cast<std::size_t>(L.witness_lower_flank)] = o.twist + dead_zone_.half_width();
  }
  if (L.witness_reversal >= 0) {
    g[static_cast<std::size_t>(L.witness_reversal)] = o.twist_rate;
    g[static_cast<std::size_t>(L.witness_zero_torque)] = o.spring_torque;
  }
}

void GearModel::on_event(std::size_t witness, double t, std::span<double> y,
                         std::span<double> d) const {
  const StateLayout& L = layout_;
  if (L.anchor_twist < 0) return;
  const int k = static_cast<int>(witness);
  GearOutputs o;
  evaluate(t, y.data(), d.data(), nullptr, &o);
  auto set_anchor = [&](double x, double torque, bool loading) {
    d[L.anchor_twist] = x;
    d[L.anchor_torque] = torque;
    d[L.anchor_loading] = loading ? 1.0 : 0.0;
  };
  if (k == L.witness_upper_flank || k == L.witness_lower_flank) {
    // Out of contact the element unloads completely; the next contact starts a virgin curve.
    set_anchor(0.0, 0.0, true);
  } else if (k == L.witness_reversal) {
    // The new direction is the sign of Delta'' at the root: Delta' there is only within the
    // location tolerance of zero, so compare with Delta' a little later along the flow.
    std::vector<double> f(layout_.size), y2(layout_.size);
    evaluate(t, y.data(), d.data(), f.data(), nullptr);
    const double h = 1e-9;
    for (std::size_t i = 0; i < y2.size(); ++i) y2[i] = y[i] + h * f[i];
    GearOutputs later;
    evaluate(t + h, y2.data(), d.data(), nullptr, &later);
    const double accel = later.twist_rate - o.twist_rate;
    d[L.twist_direction] = accel > 0 ? 1.0 : (accel < 0 ? -1.0 : -d[L.twist_direction]);
    set_anchor(o.spring_twist, o.spring_torque,
               HystereticBranchSpring::loading_after(o.spring_torque, d[L.twist_direction]));
  } else if (k == L.witness_zero_torque) {
    set_anchor(o.spring_twist, 0.0, true);
  }
}

std::string GearModel::event_kind(std::size_t witness, int direction) const {
  const int k = static_cast<int>(witness);
  if (k == layout_.witness_upper_flank) return direction > 0 ? "contact_made" : "contact_lost";
  if (k == layout_.witness_lower_flank) return direction < 0 ? "contact_made" : "contact_lost";
  if (k == layout_.witness_reversal) return "reversal";
  if (k == layout_.witness_zero_torque) return "zero_torque";
  return "event";
}

}  // namespace wavebench::model
