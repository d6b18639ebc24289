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

constexpr double kArcmin = std::numbers::pi / (180.0 * 60.0);

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// Clang before 17 does not deduce aggregate bases without it (the fuzz build uses clang).
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

double three_segment(const model::ThreeSegmentStiffness& s, double x) {
  const double ax = std::abs(x);
  const double x1 = s.t1 / s.k1;
  const double x2 = x1 + (s.t2 - s.t1) / s.k2;
  double t = 0;
  if (ax <= x1) {
    t = s.k1 * ax;
  } else if (ax <= x2) {
    t = s.t1 + s.k2 * (ax - x1);
  } else {
    t = s.t2 + s.k3 * (ax - x2);
  }
  return std::copysign(t, x);
}

double table(const model::TableStiffness& s, double x) {
  // Piecewise linear and odd-extended; the full model's PCHIP differs only between points.
  const double ax = std::abs(x);
  const auto& xs = s.twist_rad;
  const auto& ts = s.torque_nm;
  double t = 0;
  if (ax >= xs.back()) {
    const std::size_t n = xs.size();
    const double slope = (ts[n - 1] - ts[n - 2]) / (xs[n - 1] - xs[n - 2]);
    t = ts[n - 1] + slope * (ax - xs[n - 1]);
  } else {
    const auto it = std::upper_bound(xs.begin(), xs.end(), ax);
    const auto i = static_cast<std::size_t>(it - xs.begin());
    const double f = (ax - xs[i - 1]) / (xs[i] - xs[i - 1]);
    t = ts[i - 1] + f * (ts[i] - ts[i - 1]);
  }
  return std::copysign(t, x);
}

double mean_stiffness(const model::StiffnessParams& p) {
  if (p.mean_stiffness) return *p.mean_stiffness;
  return std::visit(Overloaded{[](const model::LinearPeriodicStiffness& s) { return s.k0; },
                               [](const model::CubicStiffness& s) { return s.k1; },
                               [](const model::ThreeSegmentStiffness& s) { return s.k1; },
                               [](const model::TableStiffness& s) {
                                 return s.twist_rad.size() >= 2 ? s.torque_nm[1] / s.twist_rad[1]
                                                                : 0.0;
                               },
                               [](const auto&) { return 0.0; }},
                    p.law);
}

}  // namespace

SimulatedBenchPlant::SimulatedBenchPlant(model::GearParams params, double max_substep)
    : params_(std::move(params)), max_substep_(max_substep) {
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
  const bool supported = std::visit(
      Overloaded{
          [](const model::LinearPeriodicStiffness&) { return true; },
          [](const model::CubicStiffness&) { return true; },
          [](const model::ThreeSegmentStiffness& s) { return s.k1 > 0 && s.k2 > 0 && s.k3 > 0; },
          [](const model::TableStiffness& s) {
            return s.twist_rad.size() >= 2 && s.twist_rad.size() == s.torque_nm.size();
          },
          [&](const auto&) { return params_.stiffness.mean_stiffness.has_value(); }},
      params_.stiffness.law);
  if (!supported) {
    throw std::invalid_argument(
        "stiffness law is not usable by the simulated bench (expected linear, cubic, "
        "three-segment with k1,k2,k3 > 0, a table of >= 2 points, or a hysteretic law with "
        "mean_stiffness)");
  }
  const double k_mean = mean_stiffness(params_.stiffness);
  if (!(k_mean > 0)) throw std::invalid_argument("stiffness: mean stiffness must be > 0");
  if (params_.damping.coefficient) {
    damping_ = *params_.damping.coefficient;
  } else {
    const double zeta = params_.damping.damping_ratio.value_or(0.06);
    const double n2j1 = ratio_ * ratio_ * params_.inertia_input;
    const double j_eq = n2j1 * params_.inertia_output / (n2j1 + params_.inertia_output);
    damping_ = 2 * zeta * std::sqrt(j_eq * k_mean);
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
  double e = 0;
  for (const auto& term : params_.te_terms) {
    e += term.amplitude_rad *
         std::sin(term.order_input * theta_in + term.order_output * theta_out + term.phase_rad);
  }
  return e;
}

double SimulatedBenchPlant::te_rate(double theta_in, double theta_out, double omega_in,
                                    double omega_out) const {
  double de = 0;
  for (const auto& term : params_.te_terms) {
    de += term.amplitude_rad * (term.order_input * omega_in + term.order_output * omega_out) *
          std::cos(term.order_input * theta_in + term.order_output * theta_out + term.phase_rad);
  }
  return de;
}

double SimulatedBenchPlant::backlash_filter(double twist) const {
  const double half = params_.backlash.total_rad / 2;
  if (twist > half) return twist - half;
  if (twist < -half) return twist + half;
  return 0;
}

double SimulatedBenchPlant::stiffness_torque(double x, double theta_in, double theta_out) const {
  double modulation = 1;
  for (const auto& h : params_.stiffness.modulation) {
    modulation +=
        h.amplitude * std::cos(h.order_input * theta_in + h.order_output * theta_out + h.phase_rad);
  }
  return std::visit(
      Overloaded{
          [&](const model::LinearPeriodicStiffness& s) {
            double k = s.k0;
            for (const auto& h : s.harmonics) {
              k += h.amplitude *
                   std::cos(h.order_input * theta_in + h.order_output * theta_out + h.phase_rad);
            }
            return k * x;
          },
          [&](const model::CubicStiffness& s) {
            return modulation * (s.k1 * x + s.k3 * x * x * x);
          },
          [&](const model::ThreeSegmentStiffness& s) { return modulation * three_segment(s, x); },
          [&](const model::TableStiffness& s) { return modulation * table(s, x); },
          [&](const auto&) { return *params_.stiffness.mean_stiffness * x; }},
      params_.stiffness.law);
}

double SimulatedBenchPlant::friction_torque(double omega_in) const {
  return std::visit(
      Overloaded{[](const model::NoFriction&) { return 0.0; },
                 [&](const model::CoulombStribeckFriction& f) {
                   const double stribeck =
                       f.coulomb + (f.static_torque - f.coulomb) *
                                       std::exp(-std::pow(omega_in / f.stribeck_speed, 2));
                   return stribeck * std::tanh(omega_in / f.smoothing_speed) + f.viscous * omega_in;
                 },
                 // LuGre's steady-state curve; the bristle dynamics are the full model's job.
                 [&](const model::LuGreFriction& f) {
                   const double stribeck =
                       f.coulomb + (f.static_torque - f.coulomb) *
                                       std::exp(-std::pow(omega_in / f.stribeck_speed, 2));
                   return stribeck * std::tanh(omega_in / 1e-3) + f.sigma2 * omega_in;
                 }},
      params_.friction);
}

void SimulatedBenchPlant::step(double dt) {
  if (!(dt > 0)) return;
  const int n = std::max(1, static_cast<int>(std::ceil(dt / max_substep_ - 1e-9)));
  const double h = dt / n;
  for (int i = 0; i < n; ++i) substep(h);
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
  const double e = te_excitation(s.theta_in, s.theta_out) + defect.value;
  const double twist = s.theta_in / n - s.theta_out - e;
  const double twist_rate = s.omega_in / n - s.omega_out -
                            te_rate(s.theta_in, s.theta_out, s.omega_in, s.omega_out) - defect.rate;
  const double x = backlash_filter(twist);
  double tg = 0;
  if (x != 0) {
    const double spring = stiffness_torque(x, s.theta_in, s.theta_out);
    tg = spring + damping_ * twist_rate;
    // In contact the mesh cannot pull (ElastoBacklash): damping never reverses the torque.
    tg = x > 0 ? std::max(tg, 0.0) : std::min(tg, 0.0);
  }

  const auto& load = params_.load;
  const double t_load = load.output_torque.offset +
                        load.output_torque.amplitude *
                            std::sin(2 * std::numbers::pi * load.output_torque.frequency_hz * s.t +
                                     load.output_torque.phase_rad);
  const double ripple = load.drive_ripple.offset +
                        load.drive_ripple.amplitude *
                            std::sin(2 * std::numbers::pi * load.drive_ripple.frequency_hz * s.t +
                                     load.drive_ripple.phase_rad);
  const double drag = load.output_drag_coulomb * std::tanh(s.omega_out / load.drag_smoothing_speed);

  const double acc_in = (s.motor_torque + ripple - params_.viscous_input * s.omega_in -
                         friction_torque(s.omega_in) - tg / n) /
                        j1;
  // The brake is a set-valued friction: it holds the output still when the other torques stay
  // within its setting, and slips against the motion otherwise (time-stepping friction).
  const double free_torque = tg - params_.viscous_output * s.omega_out - drag - t_load;
  const double omega_free = s.omega_out + h * free_torque / j2;
  const double hold = h * brake_limit_ / j2;
  double brake = 0;
  if (std::abs(omega_free) <= hold) {
    brake = -omega_free * j2 / h;
  } else {
    brake = -std::copysign(brake_limit_, omega_free);
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
}

model::GearParams default_bench_gear() {
  // The character of seed 004's unit (bench.md §4): no-load static TE over one output
  // revolution p2p ~5.2 arcmin, std ~1.8 arcmin, mean ~-1.75 arcmin with ~0.3 arcmin between
  // the directions, and a ~4.7 arcmin mean shift under 60 N*m. The geometry is the twin case's
  // (configs/twin/bench-unit-seed004.yaml, N = 100); amplitudes, phases, stiffness and the
  // mechanics differ from its nominal values on purpose: these are the unit's "true" ones.
  model::GearParams p;
  p.name = "simulated bench gear (true parameters)";
  p.geometry.z_flex = 200;
  p.geometry.z_circ = 202;
  p.geometry.wave_number = 2;
  p.geometry.ratio = 100;
  p.geometry.direction_sign = 1;
  p.inertia_input = 1.2e-4;  // servo rotor + wave generator
  p.inertia_output = 0.04;   // flange, torque sensor, brake rotor
  p.viscous_input = 2e-5;
  p.viscous_output = 0.05;
  const double u = 2;
  const double half_pi = std::numbers::pi / 2;
  p.te_terms = {
      // The output encoder's zero against the input's: a constant TE offset.
      {"assembly offset", model::TeFamily::kCustom, 1.75 * kArcmin, 0, 0, half_pi},
      {"output flange eccentricity (1/rev)", model::TeFamily::kOutputOnceRev, 2.4 * kArcmin, 0, 1,
       0.3},
      {"output 2/rev (Flexspline ovality)", model::TeFamily::kCustom, 0.5 * kArcmin, 0, 2, 0.9},
      {"dF_i1 (Flexspline tangential composite error)", model::TeFamily::kTangentialOutput,
       0.25 * kArcmin, u, u, 0.4},
      {"dF_i2 (fixed circular spline tangential composite error)",
       model::TeFamily::kTangentialFixed, 0.18 * kArcmin, u, 0, 1.3},
      {"Flexspline tooth pitch (z_F per output revolution)", model::TeFamily::kCustom,
       0.12 * kArcmin, 0, 200, 0.2},
      // U*z_C per wave-generator revolution: 673 Hz at 100 rpm, above a 1 kHz SYNC's Nyquist.
      {"df_i1 (base pitch)", model::TeFamily::kToothMesh, 0.03 * kArcmin, u * 202, 0, 0.3},
  };
  p.stiffness.law = model::ThreeSegmentStiffness{3.2e4, 14, 4.6e4, 48, 6.2e4};
  p.backlash.total_rad = 0.3 * kArcmin;
  p.damping.damping_ratio = 0.06;
  p.friction = model::CoulombStribeckFriction{0.02, 0.03, 0.5, 1e-5, 1e-2};
  p.load.output_drag_coulomb = 0.3;
  p.load.drag_smoothing_speed = 1e-3;
  return p;
}

}  // namespace wavebench::simdevices
