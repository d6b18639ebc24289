#include "wavebench/model/solver/rosenbrock4.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "step_size.hpp"

namespace wavebench::model::solver {
namespace {

// Hairer & Wanner's six-stage L-stable Rosenbrock 4(3) (the set of Numerical Recipes 3rd ed.,
// StepperRoss, and of Boost.Odeint's rosenbrock4), in the form that solves with
// (I/(γh) − J) and carries stage increments g_i. d4 is negative as in Hairer's RODAS (METH=1);
// Boost 1.74's odeint rosenbrock4 has it positive, which drops the method to first order on
// any problem with an explicit time dependence (y' = cos 3t shows it).
constexpr double gamma = 0.25;
constexpr double d1 = 0.25, d2 = -0.1043, d3 = 0.1035, d4 = -0.3620000000000023e-01;
constexpr double c2 = 0.386, c3 = 0.21, c4 = 0.63;
constexpr double c21 = -0.5668800000000000e+01, a21 = 0.1544000000000000e+01;
constexpr double c31 = -0.2430093356833875e+01, c32 = -0.2063599157091915e+00;
constexpr double a31 = 0.9466785280815826e+00, a32 = 0.2557011698983284e+00;
constexpr double c41 = -0.1073529058151375e+00, c42 = -0.9594562251023355e+01,
                 c43 = -0.2047028614809616e+02;
constexpr double a41 = 0.3314825187068521e+01, a42 = 0.2896124015972201e+01,
                 a43 = 0.9986419139977817e+00;
constexpr double c51 = 0.7496443313967647e+01, c52 = -0.1024680431464352e+02,
                 c53 = -0.3399990352819905e+02, c54 = 0.1170890893206160e+02;
constexpr double a51 = 0.1221224509226641e+01, a52 = 0.6019134481288629e+01,
                 a53 = 0.1253708332932087e+02, a54 = -0.6878860361058950e+00;
constexpr double c61 = 0.8083246795921522e+01, c62 = -0.7981132988064893e+01,
                 c63 = -0.3152159432874371e+02, c64 = 0.1631930543123136e+02,
                 c65 = -0.6058818238834054e+01;
// Dense output.
constexpr double d21 = 0.1012623508344586e+02, d22 = -0.7487995877610167e+01,
                 d23 = -0.3480091861555747e+02, d24 = -0.7992771707568823e+01,
                 d25 = 0.1025137723295662e+01;
constexpr double d31 = -0.6762803392801253e+00, d32 = 0.6087714651680015e+01,
                 d33 = 0.1643084320892478e+02, d34 = 0.2476722511418386e+02,
                 d35 = -0.6594389125716872e+01;

// Gustafsson's predictive controller, step ratio within [1/5, 6].
constexpr double kSafe = 0.9, kFacMax = 5.0, kFacMin = 1.0 / 6.0;

}  // namespace

Rosenbrock4::Rosenbrock4(const StepControl& control) : AdaptiveIntegrator(control) {}

void Rosenbrock4::DoInitialize(double h0) {
  const auto n = static_cast<Eigen::Index>(n_);
  for (auto* v : {&y_, &y_old_, &y_new_, &y_stage_, &f0_, &f_stage_, &dfdt_, &err_, &error_scale_,
                  &g1_, &g2_, &g3_, &g4_, &g5_, &cont3_, &cont4_}) {
    v->setZero(n);
  }
  jac_.setZero(n, n);
  iteration_matrix_.setZero(n, n);
  lu_ = Eigen::PartialPivLU<Eigen::MatrixXd>(n);
  system_->error_scale({error_scale_.data(), n_});
  validate_error_scale({error_scale_.data(), n_});
  first_step_ = true;
  h_ = control_.fixed_step > 0 ? control_.fixed_step : h0;
}

void Rosenbrock4::DoReset(std::span<const double> y) {
  for (std::size_t i = 0; i < n_; ++i) y_[static_cast<Eigen::Index>(i)] = y[i];
  y_old_ = y_;
  cont3_.setZero();
  cont4_.setZero();
  evaluate(t_, y_.data(), f0_.data());
  jacobian_current_ = false;
  last_rejected_ = false;
  first_step_ = true;
  if (h_ <= 0) {
    const auto& tol = control_.tolerances;
    h_ = detail::initial_step(
        [this](double tt, const double* yy, double* ff) { evaluate(tt, yy, ff); }, t_, y_.data(),
        f0_.data(), error_scale_.data(), n_, tol.atol, tol.rtol, 4, control_.max_step,
        y_stage_.data(), f_stage_.data());
  }
}

void Rosenbrock4::evaluate_jacobian() {
  ++counters_.jacobian_evaluations;
  const std::span<double> jac{jac_.data(), n_ * n_};
  // Eigen is column-major; the OdeSystem contract is row-major, so the transpose goes in.
  if (system_->jacobian(t_, {y_.data(), n_}, d_, jac)) {
    jac_.transposeInPlace();
  } else {
    const double sqrt_eps = std::sqrt(std::numeric_limits<double>::epsilon());
    y_stage_ = y_;
    for (std::size_t j = 0; j < n_; ++j) {
      const auto jj = static_cast<Eigen::Index>(j);
      // Perturb by a relative sqrt(eps) of the state's own size or its characteristic size.
      const double delta = sqrt_eps * std::fmax(std::fabs(y_[jj]), error_scale_[jj]);
      y_stage_[jj] = y_[jj] + delta;
      const double dy = y_stage_[jj] - y_[jj];  // exactly representable increment
      evaluate(t_, y_stage_.data(), f_stage_.data());
      jac_.col(jj) = (f_stage_ - f0_) / dy;
      y_stage_[jj] = y_[jj];
    }
  }
  // df/dt by a central difference over a fraction of the step: forcing terms (24 kHz mesh
  // excitation) vary on the step's time scale, not on the scale of |t|, and a forward
  // difference's O(dt) error costs a Rosenbrock method its order.
  const double cbrt_eps = std::cbrt(std::numeric_limits<double>::epsilon());
  const double h_scale = h_ > 0 ? h_ : 1e-6;
  const double dt =
      std::fmax(cbrt_eps * h_scale, 64 * std::numeric_limits<double>::epsilon() * std::fabs(t_));
  const double t_plus = t_ + dt, t_minus = t_ - dt;
  evaluate(t_plus, y_.data(), f_stage_.data());
  dfdt_ = f_stage_;
  evaluate(t_minus, y_.data(), f_stage_.data());
  dfdt_ = (dfdt_ - f_stage_) / (t_plus - t_minus);
  jacobian_current_ = true;
}

void Rosenbrock4::attempt(double h) {
  if (!jacobian_current_) evaluate_jacobian();
  iteration_matrix_ = -jac_;
  iteration_matrix_.diagonal().array() += 1.0 / (gamma * h);
  lu_.compute(iteration_matrix_);
  const double inv_h = 1.0 / h;

  g1_ = f0_ + (h * d1) * dfdt_;
  g1_ = lu_.solve(g1_);

  y_stage_ = y_ + a21 * g1_;
  evaluate(t_ + c2 * h, y_stage_.data(), f_stage_.data());
  g2_ = f_stage_ + (h * d2) * dfdt_ + (c21 * inv_h) * g1_;
  g2_ = lu_.solve(g2_);

  y_stage_ = y_ + a31 * g1_ + a32 * g2_;
  evaluate(t_ + c3 * h, y_stage_.data(), f_stage_.data());
  g3_ = f_stage_ + (h * d3) * dfdt_ + inv_h * (c31 * g1_ + c32 * g2_);
  g3_ = lu_.solve(g3_);

  y_stage_ = y_ + a41 * g1_ + a42 * g2_ + a43 * g3_;
  evaluate(t_ + c4 * h, y_stage_.data(), f_stage_.data());
  g4_ = f_stage_ + (h * d4) * dfdt_ + inv_h * (c41 * g1_ + c42 * g2_ + c43 * g3_);
  g4_ = lu_.solve(g4_);

  y_stage_ = y_ + a51 * g1_ + a52 * g2_ + a53 * g3_ + a54 * g4_;
  evaluate(t_ + h, y_stage_.data(), f_stage_.data());
  g5_ = f_stage_ + inv_h * (c51 * g1_ + c52 * g2_ + c53 * g3_ + c54 * g4_);
  g5_ = lu_.solve(g5_);

  y_stage_ += g5_;
  evaluate(t_ + h, y_stage_.data(), f_stage_.data());
  err_ = f_stage_ + inv_h * (c61 * g1_ + c62 * g2_ + c63 * g3_ + c64 * g4_ + c65 * g5_);
  err_ = lu_.solve(err_);
  y_new_ = y_stage_ + err_;
}

void Rosenbrock4::DoLandInPlace() {
  y_old_ = y_;
  cont3_.setZero();
  cont4_.setZero();
}

double Rosenbrock4::DoStep(double t_max) {
  const bool fixed = control_.fixed_step > 0;
  const double atol = control_.tolerances.atol;
  const double rtol = control_.tolerances.rtol;
  for (;;) {
    double h = fixed ? control_.fixed_step : h_;
    if (control_.max_step > 0 && h > control_.max_step) h = control_.max_step;
    bool truncated = false;
    double stretch = fixed ? 1.0 + 1e-9 : 1.01;
    if (control_.max_step > 0 && h * stretch > control_.max_step) stretch = 1.0;
    if (t_ + stretch * h >= t_max) {
      h = t_max - t_;
      truncated = true;
    }
    if (h <= 16 * std::numeric_limits<double>::epsilon() * std::fabs(t_)) {
      throw std::runtime_error("Rosenbrock4: step size underflow (h = " + std::to_string(h) +
                               ") at t = " + std::to_string(t_));
    }
    attempt(h);
    double err = 0;
    if (!fixed) {
      err = detail::weighted_rms(err_.data(), y_.data(), y_new_.data(), error_scale_.data(), n_,
                                 atol, rtol);
      if (!std::isfinite(err)) err = 1e10;
    }
    if (fixed || err <= 1.0) {
      ++counters_.steps;
      if (!fixed) {
        double fac = std::fmax(kFacMin, std::fmin(kFacMax, std::pow(err, 0.25) / kSafe));
        if (!first_step_) {
          double fac_pred = (h_accepted_old_ / h) * std::pow(err * err / err_old_, 0.25) / kSafe;
          fac_pred = std::fmax(kFacMin, std::fmin(kFacMax, fac_pred));
          fac = std::fmax(fac, fac_pred);
        }
        first_step_ = false;
        double h_new = h / fac;
        if (last_rejected_) h_new = std::fmin(h_new, h);
        if (truncated) h_new = std::fmax(h_new, h_);
        h_accepted_old_ = h;
        err_old_ = std::fmax(0.01, err);
        h_ = h_new;
        last_rejected_ = false;
      }
      // Dense output from this step's stage increments.
      cont3_ = d21 * g1_ + d22 * g2_ + d23 * g3_ + d24 * g4_ + d25 * g5_;
      cont4_ = d31 * g1_ + d32 * g2_ + d33 * g3_ + d34 * g4_ + d35 * g5_;
      t_old_ = t_;
      t_ = truncated ? t_max : t_ + h;
      h_last_ = h;
      y_old_.swap(y_);
      y_.swap(y_new_);
      evaluate(t_, y_.data(), f0_.data());
      jacobian_current_ = false;
      return t_;
    }
    ++counters_.rejected_steps;
    h_ = h / std::fmax(kFacMin, std::fmin(kFacMax, std::pow(err, 0.25) / kSafe));
    last_rejected_ = true;
  }
}

void Rosenbrock4::DoDenseOutput(double t, std::span<double> y) const {
  const double h = t_ - t_old_;
  const double s = h > 0 ? (t - t_old_) / h : 1.0;
  const double s1 = 1.0 - s;
  for (std::size_t i = 0; i < n_; ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    y[i] = y_old_[ii] * s1 + s * (y_[ii] + s1 * (cont3_[ii] + s * cont4_[ii]));
  }
}

}  // namespace wavebench::model::solver
