#include "wavebench/analysis/linearised_gear.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <type_traits>

#include "wavebench/model/angle_units.hpp"

namespace wavebench::analysis {
namespace {

// x >= 0 with curve(x) = torque for a curve rising from curve(0) = 0; bracket by doubling.
double invert_rising(const std::function<double(double)>& curve, double torque, double scale) {
  if (!(torque > 0)) return 0;
  double lo = 0;
  double hi = scale > 0 ? scale : 1e-6;
  for (int i = 0; i < 200 && curve(hi) < torque; ++i) hi *= 2;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (curve(mid) < torque ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

struct Tangent {
  double stiffness;
  double twist;  // x >= 0 (the law's own argument, backlash filtered)
  std::string note;
};

Tangent tangent_of(const model::LinearPeriodicStiffness& law, double t) {
  if (!(law.k0 > 0)) throw std::invalid_argument("stiffness.k0 must be > 0 to linearise");
  return {law.k0, t / law.k0, "k0 (the periodic terms average out)"};
}
Tangent tangent_of(const model::CubicStiffness& law, double t) {
  const double x = invert_rising([&](double v) { return law.k1 * v + law.k3 * v * v * v; }, t,
                                 law.k1 > 0 ? t / law.k1 : 1e-3);
  return {law.k1 + 3 * law.k3 * x * x, x, "k1 + 3 k3 x^2 at the operating twist"};
}
Tangent tangent_of(const model::ThreeSegmentStiffness& law, double t) {
  const double x1 = law.t1 / law.k1;
  const double x2 = x1 + (law.t2 - law.t1) / law.k2;
  if (t <= law.t1) return {law.k1, t / law.k1, "segment K1"};
  if (t <= law.t2) return {law.k2, x1 + (t - law.t1) / law.k2, "segment K2"};
  return {law.k3, x2 + (t - law.t2) / law.k3, "segment K3"};
}
Tangent tangent_of(const model::TableStiffness& law, double t) {
  const auto& x = law.twist_rad;
  const auto& y = law.torque_nm;
  if (x.size() < 2 || x.size() != y.size()) {
    throw std::invalid_argument("stiffness table needs >= 2 (twist, torque) pairs");
  }
  std::size_t i = 0;
  while (i + 2 < x.size() && y[i + 1] < t) ++i;
  const double slope = (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
  return {slope, x[i] + (t - y[i]) / slope, "slope of the table segment holding the torque"};
}
Tangent tangent_of(const model::HystereticBranchStiffness& law, double t) {
  // K(x) in N m/arcsec with x in arcsec; the mean of the two branches' tangents.
  auto branch_torque = [](double a, double b, double c, double x) {
    return a * x * x * x / 3 + b * x * x / 2 + c * x;
  };
  const double xl = invert_rising(
      [&](double x) { return branch_torque(law.a_load, law.b_load, law.c_load, x); }, t, 1.0);
  const double xu = invert_rising(
      [&](double x) { return branch_torque(law.a_unload, law.b_unload, law.c_unload, x); }, t, 1.0);
  const double kl = law.a_load * xl * xl + law.b_load * xl + law.c_load;
  const double ku = law.a_unload * xu * xu + law.b_unload * xu + law.c_unload;
  return {0.5 * (kl + ku) * model::kArcsecPerRad, 0.5 * (xl + xu) / model::kArcsecPerRad,
          "mean of the loading and unloading branch tangents"};
}
Tangent tangent_of(const model::FadingMemoryStiffness& law, double t) {
  auto curve = [&](double x) { return law.a * x * x * x + law.b * x * x + law.c * x; };
  const double x = invert_rising(curve, t, law.c > 0 ? t / law.c : 1e-3);
  return {3 * law.a * x * x + 2 * law.b * x + law.c, x,
          "static curve 3a x^2 + 2b x + c; the memory term adds up to A above B rad/s"};
}
Tangent tangent_of(const model::BoucWenStiffness& law, double t) {
  return {law.k, law.k > 0 ? t / law.k : 0, "k (tangent after a reversal)"};
}

}  // namespace

bool has_te_transfer(const std::string& channel) {
  static const char* names[] = {"alpha2", "omega2",     "te",          "theta2_dev",
                                "twist",  "twist_rate", "gear_torque", "omega1"};
  return std::any_of(std::begin(names), std::end(names),
                     [&](const char* n) { return channel == n; });
}

double mean_stiffness(const model::StiffnessParams& stiffness, double torque, double* twist_out,
                      std::string* note) {
  const double magnitude = std::abs(torque);
  Tangent tangent =
      std::visit([&](const auto& law) { return tangent_of(law, magnitude); }, stiffness.law);
  if (stiffness.mean_stiffness) {
    tangent.stiffness = *stiffness.mean_stiffness;
    tangent.note = "given (stiffness.mean_stiffness)";
  }
  if (!(tangent.stiffness > 0)) {
    throw std::invalid_argument("mean stiffness " + std::to_string(tangent.stiffness) +
                                " N*m/rad at the operating torque " + std::to_string(torque) +
                                " N*m, expected > 0");
  }
  if (twist_out) *twist_out = torque < 0 ? -tangent.twist : tangent.twist;
  if (note) *note = tangent.note;
  return tangent.stiffness;
}

LinearisedGear linearise_gear(const model::GearParams& params, double mean_gear_torque) {
  LinearisedGear gear;
  auto& co = gear.coefficients;
  co.inertia_input = params.inertia_input;
  co.inertia_output = params.inertia_output;
  co.ratio = params.geometry.ratio;
  if (!(co.ratio > 0) && params.geometry.z_circ > params.geometry.z_flex) {
    co.ratio = static_cast<double>(params.geometry.z_flex) /
               (params.geometry.z_circ - params.geometry.z_flex);
  }
  if (!(co.ratio > 0)) throw std::invalid_argument("geometry.ratio must be > 0 to linearise");
  double x = 0;
  co.stiffness = mean_stiffness(params.stiffness, mean_gear_torque, &x, &gear.stiffness_note);
  const double half_backlash = 0.5 * params.backlash.total_rad;
  gear.operating_twist_rad = x + (mean_gear_torque < 0 ? -half_backlash : half_backlash);
  gear.operating_torque_nm = mean_gear_torque;

  // The mesh damping is a fixed coefficient of the model: from a damping ratio it is set with
  // the mean stiffness given in the config, else the small-twist tangent (as the model does),
  // not with the operating-point tangent used for the dynamics here.
  const double n2j1 = co.ratio * co.ratio * co.inertia_input;
  const double j_eq =
      n2j1 > 0 ? n2j1 * co.inertia_output / (n2j1 + co.inertia_output) : co.inertia_output;
  if (params.damping.coefficient) {
    co.mesh_damping = *params.damping.coefficient;
  } else if (params.damping.damping_ratio) {
    const double k_damping = mean_stiffness(params.stiffness, 0.0, nullptr, nullptr);
    co.mesh_damping = 2 * *params.damping.damping_ratio * std::sqrt(j_eq * k_damping);
  }
  co.damping_input = params.viscous_input;
  co.damping_output = params.viscous_output;
  if (const auto* f = std::get_if<model::CoulombStribeckFriction>(&params.friction)) {
    co.damping_input += f->viscous;
  } else if (const auto* l = std::get_if<model::LuGreFriction>(&params.friction)) {
    co.damping_input += l->sigma2;
  }
  if (const auto* dc = std::get_if<model::DcMotorInput>(&params.input)) {
    // u = R i + K_e w (L neglected): the back EMF is a speed feedback K_m K_e / R.
    if (dc->resistance > 0)
      co.damping_input += dc->torque_constant * dc->back_emf_constant / dc->resistance;
  } else if (const auto* servo = std::get_if<model::ServoDriveInput>(&params.input)) {
    co.damping_input += servo->velocity_gain;  // proportional velocity loop acts as damping
  }
  co.input_prescribed = std::holds_alternative<model::KinematicInput>(params.input);
  gear.modes = vibration_modes(co);
  return gear;
}

namespace {

struct Matrices {
  Eigen::Matrix2d mass, damping, stiffness;
};

Matrices two_inertia(const LinearGearCoefficients& co) {
  const double n = co.ratio;
  Eigen::Matrix2d coupling;
  coupling << 1 / (n * n), -1 / n, -1 / n, 1;
  Matrices m;
  m.mass << co.inertia_input, 0, 0, co.inertia_output;
  m.stiffness = co.stiffness * coupling;
  m.damping = co.mesh_damping * coupling;
  m.damping(0, 0) += co.damping_input;
  m.damping(1, 1) += co.damping_output;
  return m;
}

}  // namespace

std::vector<VibrationMode> vibration_modes(const LinearGearCoefficients& co) {
  std::vector<VibrationMode> modes;
  if (co.input_prescribed) {
    VibrationMode mode;
    const double wn = std::sqrt(co.stiffness / co.inertia_output);
    mode.natural_frequency_hz = wn / (2 * std::numbers::pi);
    mode.damping_ratio = (co.mesh_damping + co.damping_output) / (2 * co.inertia_output * wn);
    mode.shape_output = 1;
    modes.push_back(mode);
    return modes;
  }
  const Matrices m = two_inertia(co);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> eig(m.stiffness, m.mass);
  // State-space eigenvalues for the damping ratios (damping need not be proportional).
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  const Eigen::Matrix2d minv = m.mass.inverse();
  a.topRightCorner<2, 2>() = Eigen::Matrix2d::Identity();
  a.bottomLeftCorner<2, 2>() = -minv * m.stiffness;
  a.bottomRightCorner<2, 2>() = -minv * m.damping;
  const Eigen::Vector4cd lambda = Eigen::EigenSolver<Eigen::Matrix4d>(a).eigenvalues();
  const double largest = eig.eigenvalues().cwiseAbs().maxCoeff();
  for (int i = 0; i < 2; ++i) {
    const double w2 = eig.eigenvalues()(i);
    if (w2 <= 1e-9 * largest) continue;  // rigid-body rotation of the whole drive train
    const double wn = std::sqrt(w2);
    VibrationMode mode;
    mode.natural_frequency_hz = wn / (2 * std::numbers::pi);
    const Eigen::Vector2d phi = eig.eigenvectors().col(i);
    // Modal projection as the fallback when the state-space pair is overdamped (real).
    mode.damping_ratio = phi.dot(m.damping * phi) / (2 * wn * phi.dot(m.mass * phi));
    double best = 1e300;
    for (int k = 0; k < 4; ++k) {
      if (lambda(k).imag() <= 0) continue;
      const double distance = std::abs(std::abs(lambda(k)) - wn);
      if (distance < best) {
        best = distance;
        mode.damping_ratio = -lambda(k).real() / std::abs(lambda(k));
      }
    }
    const double in = phi(0) / co.ratio;
    const double out = phi(1);
    const double scale = std::max(std::abs(in), std::abs(out));
    const double sign = out < 0 ? -1.0 : 1.0;
    mode.shape_input = sign * in / scale;
    mode.shape_output = sign * out / scale;
    modes.push_back(mode);
  }
  std::sort(modes.begin(), modes.end(), [](const auto& p, const auto& q) {
    return p.natural_frequency_hz < q.natural_frequency_hz;
  });
  return modes;
}

std::complex<double> te_transfer(const LinearGearCoefficients& co, const std::string& channel,
                                 double frequency_hz) {
  using cd = std::complex<double>;
  const cd s(0, 2 * std::numbers::pi * frequency_hz);
  const cd gear = co.stiffness + co.mesh_damping * s;  // torque per unit twist
  cd q1 = 0;                                           // theta1 deviation
  cd q2 = 0;                                           // theta2 deviation
  if (co.input_prescribed) {
    q2 = -gear /
         (co.inertia_output * s * s + (co.mesh_damping + co.damping_output) * s + co.stiffness);
  } else {
    const Matrices m = two_inertia(co);
    const Eigen::Matrix2cd dynamic =
        m.mass.cast<cd>() * (s * s) + m.damping.cast<cd>() * s + m.stiffness.cast<cd>();
    Eigen::Vector2cd force;
    force << gear / co.ratio, -gear;  // the TE enters the twist with a minus sign
    const Eigen::Vector2cd q = dynamic.partialPivLu().solve(force);
    q1 = q(0);
    q2 = q(1);
  }
  const cd twist = q1 / co.ratio - q2 - 1.0;
  if (channel == "theta2_dev") return q2;
  if (channel == "te") return q2 - q1 / co.ratio;
  if (channel == "omega2") return s * q2;
  if (channel == "alpha2") return s * s * q2;
  if (channel == "omega1") return s * q1;
  if (channel == "twist") return twist;
  if (channel == "twist_rate") return s * twist;
  if (channel == "gear_torque") return gear * twist;
  throw std::invalid_argument("analysis.spectrum.signal = '" + channel +
                              "' has no TE transfer function; expected alpha2, omega2, te, "
                              "theta2_dev, twist, twist_rate, gear_torque or omega1");
}

std::complex<double> Polynomial::operator()(std::complex<double> s) const {
  std::complex<double> value = 0;
  for (double c : coefficients) value = value * s + c;
  return value;
}

namespace {

std::vector<double> multiply(const std::vector<double>& p, const std::vector<double>& q) {
  std::vector<double> r(p.size() + q.size() - 1, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = 0; j < q.size(); ++j) r[i + j] += p[i] * q[j];
  }
  return r;
}

std::vector<double> add(std::vector<double> p, std::vector<double> q) {
  if (p.size() < q.size()) std::swap(p, q);
  const std::size_t shift = p.size() - q.size();
  for (std::size_t i = 0; i < q.size(); ++i) p[shift + i] += q[i];
  return p;
}

}  // namespace

TransferFunction dc_motor_output_angle_transfer(const DcMotorGearConstants& k) {
  if (!(k.resistance > 0)) throw std::invalid_argument("resistance must be > 0 for G(s)");
  // theta_j = N theta_z P2 / G from the load equation, into the motor equation:
  // G(s) = K_m N G / (R [N^2 P1 P2 + G (J_z s^2 + C_z s)]),
  // P1 = J_j s^2 + (C_j + K_m K_e / R) s, P2 = J_z s^2 + (C_z + c) s + K, G = c s + K.
  const double n = k.ratio;
  const std::vector<double> gear{k.mesh_damping, k.stiffness};
  const std::vector<double> p1{
      k.inertia_motor, k.damping_motor + k.torque_constant * k.back_emf_constant / k.resistance, 0};
  const std::vector<double> p2{k.inertia_load, k.damping_load + k.mesh_damping, k.stiffness};
  const std::vector<double> load{k.inertia_load, k.damping_load, 0};
  std::vector<double> den = add(multiply(multiply(p1, p2), {n * n}), multiply(gear, load));
  for (double& c : den) c *= k.resistance;
  std::vector<double> num = multiply(gear, {k.torque_constant * n});
  // A zero leading coefficient (no mesh damping) would leave a degree the polynomial lacks.
  while (num.size() > 1 && num.front() == 0) num.erase(num.begin());
  return {Polynomial{num}, Polynomial{den}};
}

}  // namespace wavebench::analysis
