#include "wavebench/model/elastic_stiffness.hpp"

// Boost 1.74's pchip calls isnan unqualified; <math.h> puts it in the global namespace.
#include <math.h>

#include <algorithm>
#include <boost/math/interpolators/pchip.hpp>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace wavebench::model {
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

double odd(double x, double magnitude) noexcept {
  return x < 0.0 ? -magnitude : magnitude;
}

}  // namespace

// --- 3: three segments ---------------------------------------------------------------------
ThreeSegmentCurve::ThreeSegmentCurve(const ThreeSegmentStiffness& p) : p_(p) {
  if (!(p.k1 > 0) || !(p.k2 > 0) || !(p.k3 > 0)) {
    throw std::invalid_argument("stiffness three-segment k1/k2/k3 = " + num(p.k1) + "/" +
                                num(p.k2) + "/" + num(p.k3) + " N*m/rad: expected all > 0");
  }
  if (!(p.t1 > 0) || !(p.t2 > p.t1)) {
    throw std::invalid_argument("stiffness three-segment t1/t2 = " + num(p.t1) + "/" + num(p.t2) +
                                " N*m: expected 0 < t1 < t2");
  }
  x1_ = p.t1 / p.k1;
  x2_ = x1_ + (p.t2 - p.t1) / p.k2;
}

double ThreeSegmentCurve::torque(double x) const noexcept {
  const double a = std::abs(x);
  double t = 0.0;
  if (a <= x1_) {
    t = p_.k1 * a;
  } else if (a <= x2_) {
    t = p_.t1 + p_.k2 * (a - x1_);
  } else {
    t = p_.t2 + p_.k3 * (a - x2_);
  }
  return odd(x, t);
}

double ThreeSegmentCurve::twist_at(double torque) const noexcept {
  const double a = std::abs(torque);
  double x = 0.0;
  if (a <= p_.t1) {
    x = a / p_.k1;
  } else if (a <= p_.t2) {
    x = x1_ + (a - p_.t1) / p_.k2;
  } else {
    x = x2_ + (a - p_.t2) / p_.k3;
  }
  return odd(torque, x);
}

// --- 4: measured table -----------------------------------------------------------------------
struct TableCurve::Interpolant {
  std::optional<boost::math::interpolators::pchip<std::vector<double>>> pchip;
  std::vector<double> x, y;  // kept for the linear fallback with fewer than four points
  double operator()(double a) const {
    if (pchip) return (*pchip)(a);
    const auto it = std::upper_bound(x.begin(), x.end(), a);
    const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - x.begin()));
    const double f = (a - x[i - 1]) / (x[i] - x[i - 1]);
    return y[i - 1] + f * (y[i] - y[i - 1]);
  }
};

TableCurve::TableCurve(const TableStiffness& p) {
  const auto n = p.twist_rad.size();
  if (n < 2 || p.torque_nm.size() != n) {
    throw std::invalid_argument("stiffness table: twist and torque columns have " +
                                std::to_string(n) + " and " + std::to_string(p.torque_nm.size()) +
                                " points: expected the same count, at least 2");
  }
  if (p.twist_rad[0] != 0.0 || p.torque_nm[0] != 0.0) {
    throw std::invalid_argument("stiffness table first point (" + num(p.twist_rad[0]) + " rad, " +
                                num(p.torque_nm[0]) + " N*m): expected (0, 0)");
  }
  for (std::size_t i = 1; i < n; ++i) {
    if (!(p.twist_rad[i] > p.twist_rad[i - 1]) || !(p.torque_nm[i] >= p.torque_nm[i - 1])) {
      throw std::invalid_argument("stiffness table point " + std::to_string(i) + " (" +
                                  num(p.twist_rad[i]) + " rad, " + num(p.torque_nm[i]) +
                                  " N*m): expected twist strictly and torque monotonically "
                                  "ascending");
    }
  }
  auto interp = std::make_shared<Interpolant>();
  x_last_ = p.twist_rad.back();
  t_last_ = p.torque_nm.back();
  slope_last_ =
      (p.torque_nm[n - 1] - p.torque_nm[n - 2]) / (p.twist_rad[n - 1] - p.twist_rad[n - 2]);
  slope0_ = p.torque_nm[1] / p.twist_rad[1];
  if (n >= 4) {
    std::vector<double> x = p.twist_rad;
    std::vector<double> y = p.torque_nm;
    // The odd extension is C1 at zero when both halves start with the same slope.
    interp->pchip.emplace(std::move(x), std::move(y), slope0_, slope_last_);
  } else {
    interp->x = p.twist_rad;
    interp->y = p.torque_nm;
  }
  interp_ = std::move(interp);
}

TableCurve::~TableCurve() = default;
TableCurve::TableCurve(const TableCurve&) = default;
TableCurve& TableCurve::operator=(const TableCurve&) = default;

double TableCurve::torque(double x) const noexcept {
  const double a = std::abs(x);
  const double t = a >= x_last_ ? t_last_ + slope_last_ * (a - x_last_) : (*interp_)(a);
  return odd(x, t);
}

// --- forms 1-4 with modulation ---------------------------------------------------------------
bool is_elastic(const StiffnessLaw& law) noexcept {
  return std::holds_alternative<LinearPeriodicStiffness>(law) ||
         std::holds_alternative<CubicStiffness>(law) ||
         std::holds_alternative<ThreeSegmentStiffness>(law) ||
         std::holds_alternative<TableStiffness>(law);
}

namespace {
std::variant<std::monostate, LinearPeriodicStiffness, CubicStiffness, ThreeSegmentStiffness,
             TableStiffness>
elastic_law(const StiffnessLaw& law) {
  if (const auto* l = std::get_if<LinearPeriodicStiffness>(&law)) return *l;
  if (const auto* c = std::get_if<CubicStiffness>(&law)) return *c;
  if (const auto* s = std::get_if<ThreeSegmentStiffness>(&law)) return *s;
  if (const auto* t = std::get_if<TableStiffness>(&law)) return *t;
  throw std::invalid_argument("stiffness law: expected a memoryless form (1-4)");
}
}  // namespace

ElasticStiffness::ElasticStiffness(const StiffnessParams& params)
    : curve_(Linear{0.0}), relative_(params.modulation) {
  const auto law = elastic_law(params.law);
  if (const auto* l = std::get_if<LinearPeriodicStiffness>(&law)) {
    if (!(l->k0 > 0)) {
      throw std::invalid_argument("stiffness.k0 = " + num(l->k0) + " N*m/rad: expected > 0");
    }
    curve_ = Linear{l->k0};
    absolute_ = PeriodicModulation(l->harmonics);
  } else if (const auto* c = std::get_if<CubicStiffness>(&law)) {
    if (!(c->k1 > 0)) {
      throw std::invalid_argument("stiffness.k1 = " + num(c->k1) + " N*m/rad: expected > 0");
    }
    curve_ = *c;
  } else if (const auto* s = std::get_if<ThreeSegmentStiffness>(&law)) {
    curve_ = ThreeSegmentCurve(*s);
  } else if (const auto* t = std::get_if<TableStiffness>(&law)) {
    curve_ = TableCurve(*t);
  }
}

double ElasticStiffness::torque_unmodulated(double x) const noexcept {
  switch (curve_.index()) {
    case 0:
      return std::get<0>(curve_).k0 * x;
    case 1: {
      const auto& c = std::get<1>(curve_);
      return (c.k1 + c.k3 * x * x) * x;
    }
    case 2:
      return std::get<2>(curve_).torque(x);
    default:
      return std::get<3>(curve_).torque(x);
  }
}

double ElasticStiffness::torque(double x, double theta1, double theta2) const noexcept {
  double t = torque_unmodulated(x);
  if (!relative_.empty()) t *= 1.0 + relative_.sum(theta1, theta2);
  if (!absolute_.empty()) t += x * absolute_.sum(theta1, theta2);
  return t;
}

double ElasticStiffness::small_twist_stiffness() const noexcept {
  switch (curve_.index()) {
    case 0:
      return std::get<0>(curve_).k0;
    case 1:
      return std::get<1>(curve_).k1;
    case 2: {
      const double h = 1e-9;
      return std::get<2>(curve_).torque(h) / h;
    }
    default:
      return std::get<3>(curve_).initial_slope();
  }
}

}  // namespace wavebench::model
