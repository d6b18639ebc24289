#include "wavebench/model/kinematic_motion.hpp"

// Boost 1.74's pchip calls isnan unqualified; <math.h> puts it in the global namespace.
#include <math.h>

#include <algorithm>
#include <boost/math/interpolators/pchip.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace wavebench::model {

struct KinematicMotion::Trace {
  std::optional<boost::math::interpolators::pchip<std::vector<double>>> pchip;
  std::vector<double> t, theta;  // linear fallback below four samples
  double t0 = 0, t1 = 0, theta0 = 0, theta1 = 0, omega0 = 0, omega1 = 0;

  double angle(double s) const {
    if (pchip) return (*pchip)(s);
    const auto it = std::upper_bound(t.begin(), t.end(), s);
    const auto i = static_cast<std::size_t>(
        std::clamp<std::ptrdiff_t>(it - t.begin(), 1, static_cast<std::ptrdiff_t>(t.size()) - 1));
    return theta[i - 1] + (s - t[i - 1]) * (theta[i] - theta[i - 1]) / (t[i] - t[i - 1]);
  }
  double speed(double s) const {
    if (pchip) return pchip->prime(s);
    const auto it = std::upper_bound(t.begin(), t.end(), s);
    const auto i = static_cast<std::size_t>(
        std::clamp<std::ptrdiff_t>(it - t.begin(), 1, static_cast<std::ptrdiff_t>(t.size()) - 1));
    return (theta[i] - theta[i - 1]) / (t[i] - t[i - 1]);
  }
};

KinematicMotion::KinematicMotion(const KinematicInput& p) : speed_(p.speed), ramp_(p.ramp_time) {
  if (p.ramp_time < 0) {
    throw std::invalid_argument("input.ramp_time = " + std::to_string(p.ramp_time) +
                                " s: expected >= 0");
  }
  if (p.trace_t.empty()) return;
  const auto n = p.trace_t.size();
  if (n < 2 || p.trace_theta.size() != n) {
    throw std::invalid_argument("input trace has " + std::to_string(n) + " times and " +
                                std::to_string(p.trace_theta.size()) +
                                " angles: expected the same count, at least 2");
  }
  for (std::size_t i = 1; i < n; ++i) {
    if (!(p.trace_t[i] > p.trace_t[i - 1])) {
      throw std::invalid_argument("input trace time[" + std::to_string(i) +
                                  "] = " + std::to_string(p.trace_t[i]) +
                                  " s: expected strictly ascending times");
    }
  }
  auto tr = std::make_shared<Trace>();
  if (n >= 4) {
    tr->pchip.emplace(std::vector<double>(p.trace_t), std::vector<double>(p.trace_theta));
  } else {
    tr->t = p.trace_t;
    tr->theta = p.trace_theta;
  }
  tr->t0 = p.trace_t.front();
  tr->t1 = p.trace_t.back();
  tr->theta0 = tr->angle(tr->t0);
  tr->theta1 = tr->angle(tr->t1);
  tr->omega0 = tr->speed(tr->t0);
  tr->omega1 = tr->speed(tr->t1);
  trace_ = std::move(tr);
}

KinematicMotion::~KinematicMotion() = default;
KinematicMotion::KinematicMotion(const KinematicMotion&) = default;
KinematicMotion& KinematicMotion::operator=(const KinematicMotion&) = default;

InputMotion KinematicMotion::at(double t) const noexcept {
  if (trace_) {
    const Trace& tr = *trace_;
    // Outside the trace: continue at the end speed.
    if (t <= tr.t0) return {tr.theta0 + tr.omega0 * (t - tr.t0), tr.omega0, 0.0};
    if (t >= tr.t1) return {tr.theta1 + tr.omega1 * (t - tr.t1), tr.omega1, 0.0};
    const double h = 1e-6 * (tr.t1 - tr.t0);
    const double a = std::clamp(t - h, tr.t0, tr.t1);
    const double b = std::clamp(t + h, tr.t0, tr.t1);
    return {tr.angle(t), tr.speed(t), (tr.speed(b) - tr.speed(a)) / (b - a)};
  }
  if (ramp_ > 0 && t < ramp_) {
    if (t <= 0) return {0.0, 0.0, 0.0};
    const double acc = speed_ / ramp_;
    return {0.5 * acc * t * t, acc * t, acc};
  }
  if (ramp_ > 0) return {speed_ * (t - 0.5 * ramp_), speed_, 0.0};
  return {speed_ * t, speed_, 0.0};
}

}  // namespace wavebench::model
