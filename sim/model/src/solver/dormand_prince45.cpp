#include "wavebench/model/solver/dormand_prince45.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "step_size.hpp"

namespace wavebench::model::solver {
namespace {

// Butcher tableau of DOPRI5 (Dormand & Prince 1980; Hairer, Nørsett & Wanner, Table II.5.2).
constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
constexpr double a21 = 1.0 / 5;
constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561,
                 a54 = -212.0 / 729;
constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                 a65 = -5103.0 / 18656;
constexpr double a71 = 35.0 / 384, a73 = 500.0 / 1113, a74 = 125.0 / 192, a75 = -2187.0 / 6784,
                 a76 = 11.0 / 84;
// 5th minus embedded 4th order weights.
constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                 e6 = 22.0 / 525, e7 = -1.0 / 40;
// Continuous extension (Hairer's CONTD5, Shampine's 4th-order interpolant).
constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                 d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                 d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;

// PI controller of DOPRI5: beta = 0.04, safety 0.9, step ratio within [0.2, 10].
constexpr double kBeta = 0.04;
constexpr double kExpo1 = 0.2 - kBeta * 0.75;
constexpr double kSafe = 0.9;
constexpr double kFacMin = 0.2, kFacMax = 10.0;

}  // namespace

DormandPrince45::DormandPrince45(const StepControl& control) : AdaptiveIntegrator(control) {}

void DormandPrince45::DoInitialize(double h0) {
  for (auto* v : {&y_, &y_old_, &y_stage_, &y_new_, &error_scale_, &k1_, &k2_, &k3_, &k4_, &k5_,
                  &k6_, &k7_, &r1_, &r2_, &r3_, &r4_, &r5_}) {
    v->assign(n_, 0.0);
  }
  system_->error_scale(error_scale_);
  validate_error_scale(error_scale_);
  err_old_ = 1e-4;  // PI controller memory (Hairer's facold)
  last_rejected_ = false;
  h_ = control_.fixed_step > 0 ? control_.fixed_step : h0;
}

void DormandPrince45::DoReset(std::span<const double> y) {
  std::copy(y.begin(), y.end(), y_.begin());
  y_old_ = y_;
  evaluate(t_, y_.data(), k1_.data());
  k7_ = k1_;
  dense_ready_ = false;
  // The dense output of a zero-length step is the point itself.
  r1_ = y_;
  for (std::size_t i = 0; i < n_; ++i) r2_[i] = r3_[i] = r4_[i] = r5_[i] = 0;
  dense_ready_ = true;
  if (h_ <= 0) {
    const auto& tol = control_.tolerances;
    h_ = detail::initial_step(
        [this](double tt, const double* yy, double* ff) { evaluate(tt, yy, ff); }, t_, y_.data(),
        k1_.data(), error_scale_.data(), n_, tol.atol, tol.rtol, 5, control_.max_step, k2_.data(),
        k3_.data());
  }
  last_rejected_ = false;
}

void DormandPrince45::DoLandInPlace() {
  y_old_ = y_;
  k7_ = k1_;
  r1_ = y_;
  for (std::size_t i = 0; i < n_; ++i) r2_[i] = r3_[i] = r4_[i] = r5_[i] = 0;
  dense_ready_ = true;
}

double DormandPrince45::DoStep(double t_max) {
  const double atol = control_.tolerances.atol;
  const double rtol = control_.tolerances.rtol;
  const bool fixed = control_.fixed_step > 0;
  const std::size_t n = n_;
  double* y = y_.data();
  double* ys = y_stage_.data();
  double* yn = y_new_.data();
  double *k1 = k1_.data(), *k2 = k2_.data(), *k3 = k3_.data(), *k4 = k4_.data(), *k5 = k5_.data(),
         *k6 = k6_.data(), *k7 = k7_.data();

  for (;;) {
    double h = fixed ? control_.fixed_step : h_;
    if (control_.max_step > 0 && h > control_.max_step) h = control_.max_step;
    bool truncated = false;
    // Stretch by up to 1 % rather than leave a sliver of a step before t_max (never past a
    // fixed or maximum step).
    double stretch = fixed ? 1.0 + 1e-9 : 1.01;
    if (control_.max_step > 0 && h * stretch > control_.max_step) stretch = 1.0;
    if (t_ + stretch * h >= t_max) {
      h = t_max - t_;
      truncated = true;
    }
    if (h <= 16 * std::numeric_limits<double>::epsilon() * std::fabs(t_)) {
      throw std::runtime_error("DormandPrince45: step size underflow (h = " + std::to_string(h) +
                               ") at t = " + std::to_string(t_) +
                               "; the problem may be stiff, try the Rosenbrock method");
    }

    for (std::size_t i = 0; i < n; ++i) ys[i] = y[i] + h * a21 * k1[i];
    evaluate(t_ + c2 * h, ys, k2);
    for (std::size_t i = 0; i < n; ++i) ys[i] = y[i] + h * (a31 * k1[i] + a32 * k2[i]);
    evaluate(t_ + c3 * h, ys, k3);
    for (std::size_t i = 0; i < n; ++i) {
      ys[i] = y[i] + h * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
    }
    evaluate(t_ + c4 * h, ys, k4);
    for (std::size_t i = 0; i < n; ++i) {
      ys[i] = y[i] + h * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
    }
    evaluate(t_ + c5 * h, ys, k5);
    for (std::size_t i = 0; i < n; ++i) {
      ys[i] = y[i] + h * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
    }
    const double t_new = truncated ? t_max : t_ + h;
    evaluate(t_new, ys, k6);
    for (std::size_t i = 0; i < n; ++i) {
      yn[i] = y[i] + h * (a71 * k1[i] + a73 * k3[i] + a74 * k4[i] + a75 * k5[i] + a76 * k6[i]);
    }
    evaluate(t_new, yn, k7);

    double err = 0;
    if (!fixed) {
      // The error vector goes into the stage buffer, which is free now.
      for (std::size_t i = 0; i < n; ++i) {
        ys[i] = h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
      }
      err = detail::weighted_rms(ys, y, yn, error_scale_.data(), n, atol, rtol);
      if (!std::isfinite(err)) err = 1e10;
    }

    if (fixed || err <= 1.0) {
      ++counters_.steps;
      if (!fixed) {
        const double fac11 = std::pow(err, kExpo1);
        double fac = fac11 / std::pow(err_old_, kBeta);
        fac = std::fmax(1.0 / kFacMax, std::fmin(1.0 / kFacMin, fac / kSafe));
        double h_new = h / fac;
        if (last_rejected_) h_new = std::fmin(h_new, h);
        // A step cut short to land on t_max says nothing about the step the problem allows.
        if (truncated) h_new = std::fmax(h_new, h_);
        err_old_ = std::fmax(err, 1e-4);
        h_ = h_new;
        last_rejected_ = false;
      }
      t_old_ = t_;
      t_ = t_new;
      h_last_ = h;
      y_old_.swap(y_);
      y_.swap(y_new_);
      // FSAL: the last stage is the next step's first. k1 keeps f(t_old) for dense output
      // until the next step overwrites it; swap so k1_ holds f(t_new) and k7_ f(t_old).
      k1_.swap(k7_);
      dense_ready_ = false;
      return t_;
    }
    ++counters_.rejected_steps;
    const double fac11 = std::pow(err, kExpo1);
    h_ = h / std::fmin(1.0 / kFacMin, fac11 / kSafe);
    last_rejected_ = true;
  }
}

void DormandPrince45::prepare_dense_output() const {
  const double h = h_last_;
  // After step(): k1_ = f(t_new), k7_ = f(t_old), the other stages are the step's own.
  const double *f_old = k7_.data(), *f_new = k1_.data();
  for (std::size_t i = 0; i < n_; ++i) {
    const double ydiff = y_[i] - y_old_[i];
    const double bspl = h * f_old[i] - ydiff;
    r1_[i] = y_old_[i];
    r2_[i] = ydiff;
    r3_[i] = bspl;
    r4_[i] = ydiff - h * f_new[i] - bspl;
    r5_[i] =
        h * (d1 * f_old[i] + d3 * k3_[i] + d4 * k4_[i] + d5 * k5_[i] + d6 * k6_[i] + d7 * f_new[i]);
  }
  dense_ready_ = true;
}

void DormandPrince45::DoDenseOutput(double t, std::span<double> y) const {
  if (!dense_ready_) prepare_dense_output();
  const double h = t_ - t_old_;
  const double s = h > 0 ? (t - t_old_) / h : 1.0;
  const double s1 = 1.0 - s;
  for (std::size_t i = 0; i < n_; ++i) {
    y[i] = r1_[i] + s * (r2_[i] + s1 * (r3_[i] + s * (r4_[i] + s1 * r5_[i])));
  }
}

}  // namespace wavebench::model::solver
