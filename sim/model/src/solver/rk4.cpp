#include "wavebench/model/solver/rk4.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace wavebench::model::solver {

Rk4::Rk4(double step) {
  h_ = step;
  if (!(std::isfinite(step) && step > 0)) {
    throw std::invalid_argument("solver option fixed_step = " + std::to_string(step) +
                                ": expected a finite step > 0 [s] for Rk4");
  }
}

void Rk4::DoInitialize(double /*h0*/) {
  for (auto* v : {&y_, &y_old_, &f_, &f_old_, &k2_, &k3_, &k4_, &y_stage_}) v->assign(n_, 0.0);
}

void Rk4::DoReset(std::span<const double> y) {
  std::copy(y.begin(), y.end(), y_.begin());
  y_old_ = y_;
  evaluate(t_, y_.data(), f_.data());
  f_old_ = f_;
}

void Rk4::DoLandInPlace() {
  y_old_ = y_;
  f_old_ = f_;
}

double Rk4::DoStep(double t_max) {
  const std::size_t n = n_;
  double h = h_;
  bool truncated = false;
  // A step within rounding of t_max lands on it instead of leaving a sliver.
  if (t_ + h * (1 + 1e-9) >= t_max) {
    h = t_max - t_;
    truncated = true;
  }
  y_old_.swap(y_);
  f_old_.swap(f_);
  const double* y = y_old_.data();
  const double* k1 = f_old_.data();
  double* ys = y_stage_.data();
  double *k2 = k2_.data(), *k3 = k3_.data(), *k4 = k4_.data();
  const double half = 0.5 * h;
  for (std::size_t i = 0; i < n; ++i) ys[i] = y[i] + half * k1[i];
  evaluate(t_ + half, ys, k2);
  for (std::size_t i = 0; i < n; ++i) ys[i] = y[i] + half * k2[i];
  evaluate(t_ + half, ys, k3);
  const double t_new = truncated ? t_max : t_ + h;
  for (std::size_t i = 0; i < n; ++i) ys[i] = y[i] + h * k3[i];
  evaluate(t_new, ys, k4);
  double* yn = y_.data();
  const double sixth = h / 6.0;
  for (std::size_t i = 0; i < n; ++i) {
    yn[i] = y[i] + sixth * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
  }
  // The end-point slope serves the Hermite interpolant now and the next step's first stage.
  evaluate(t_new, yn, f_.data());
  t_old_ = t_;
  t_ = t_new;
  ++counters_.steps;
  return t_;
}

void Rk4::DoDenseOutput(double t, std::span<double> y) const {
  const double h = t_ - t_old_;
  if (!(h > 0)) {
    std::copy(y_.begin(), y_.end(), y.begin());
    return;
  }
  const double s = (t - t_old_) / h;
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
  const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  for (std::size_t i = 0; i < n_; ++i) {
    y[i] = h00 * y_old_[i] + h * h10 * f_old_[i] + h01 * y_[i] + h * h11 * f_[i];
  }
}

}  // namespace wavebench::model::solver
