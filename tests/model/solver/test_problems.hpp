#pragma once
// Problems with closed-form solutions, shared by the solver test files.

#include <cmath>
#include <numbers>
#include <span>

#include "wavebench/model/solver/ode_system.hpp"

namespace wavebench::model::solver::testing {

// y' = -lambda*y; y = y0 * exp(-lambda*t).
class ExponentialDecay final : public OdeSystem {
 public:
  explicit ExponentialDecay(double lambda) : lambda_(lambda) {}
  std::size_t continuous_size() const override { return 1; }
  void derivatives(double, std::span<const double> y, std::span<const double>,
                   std::span<double> dydt) const override {
    dydt[0] = -lambda_ * y[0];
  }
  double exact(double t, double y0) const { return y0 * std::exp(-lambda_ * t); }

 private:
  double lambda_;
};

// x'' + 2*zeta*w0*x' + w0^2*x = force*cos(w_force*t), state (x, v).
class LinearOscillator final : public OdeSystem {
 public:
  LinearOscillator(double w0, double zeta, double force = 0, double w_force = 0,
                   bool analytic_jacobian = false)
      : w0_(w0),
        zeta_(zeta),
        force_(force),
        w_force_(w_force),
        analytic_jacobian_(analytic_jacobian) {}
  std::size_t continuous_size() const override { return 2; }
  void derivatives(double t, std::span<const double> y, std::span<const double>,
                   std::span<double> dydt) const override {
    dydt[0] = y[1];
    dydt[1] = -w0_ * w0_ * y[0] - 2 * zeta_ * w0_ * y[1] + force_ * std::cos(w_force_ * t);
  }
  bool jacobian(double, std::span<const double>, std::span<const double>,
                std::span<double> j) const override {
    if (!analytic_jacobian_) return false;
    j[0] = 0;
    j[1] = 1;
    j[2] = -w0_ * w0_;
    j[3] = -2 * zeta_ * w0_;
    return true;
  }

  // Free response from (x0, v0), underdamped or undamped (zeta < 1), no force.
  void free_response(double t, double x0, double v0, double& x, double& v) const {
    const double sigma = zeta_ * w0_;
    const double wd = w0_ * std::sqrt(1 - zeta_ * zeta_);
    const double a = x0, b = (v0 + sigma * x0) / wd;
    const double e = std::exp(-sigma * t), c = std::cos(wd * t), s = std::sin(wd * t);
    x = e * (a * c + b * s);
    v = e * (-sigma * (a * c + b * s) + wd * (-a * s + b * c));
  }

  // Steady-state forced response X*cos(w t - phi); starting on it, the solution stays on it.
  void steady_state(double t, double& x, double& v) const {
    const double w = w_force_;
    const double re = w0_ * w0_ - w * w, im = 2 * zeta_ * w0_ * w;
    const double amplitude = force_ / std::hypot(re, im);
    const double phi = std::atan2(im, re);
    x = amplitude * std::cos(w * t - phi);
    v = -amplitude * w * std::sin(w * t - phi);
  }

  double energy(std::span<const double> y) const {
    return 0.5 * y[1] * y[1] + 0.5 * w0_ * w0_ * y[0] * y[0];
  }

 private:
  double w0_, zeta_, force_, w_force_;
  bool analytic_jacobian_;
};

// y' = y*cos(t); y = y0*exp(sin t). Smooth, nonlinear in t, for convergence orders.
class ExpSine final : public OdeSystem {
 public:
  std::size_t continuous_size() const override { return 1; }
  void derivatives(double t, std::span<const double> y, std::span<const double>,
                   std::span<double> dydt) const override {
    dydt[0] = y[0] * std::cos(t);
  }
  bool jacobian(double t, std::span<const double>, std::span<const double>,
                std::span<double> j) const override {
    j[0] = std::cos(t);
    return true;
  }
  static double exact(double t) { return std::exp(std::sin(t)); }
};

// y' = -2*t*y^2; y = 1/(1 + t^2) from y(0) = 1. Nonlinear and time-dependent.
class Rational final : public OdeSystem {
 public:
  std::size_t continuous_size() const override { return 1; }
  void derivatives(double t, std::span<const double> y, std::span<const double>,
                   std::span<double> dydt) const override {
    dydt[0] = -2 * t * y[0] * y[0];
  }
  static double exact(double t) { return 1 / (1 + t * t); }
};

// y1' = r2*y2, y2' = -r2*y1 with r2 = y1^2 + y2^2: a circle of radius r run at angular speed
// r^2, y = r*(cos r^2 t, -sin r^2 t) from (r, 0). Nonlinear and coupled.
class NonlinearRotation final : public OdeSystem {
 public:
  std::size_t continuous_size() const override { return 2; }
  void derivatives(double, std::span<const double> y, std::span<const double>,
                   std::span<double> dydt) const override {
    const double r2 = y[0] * y[0] + y[1] * y[1];
    dydt[0] = r2 * y[1];
    dydt[1] = -r2 * y[0];
  }
  static double exact_first(double t, double r) { return r * std::cos(r * r * t); }
};

// Prothero–Robinson: y' = -k*(y - cos t) - sin t; y = cos t + (y0 - 1)*exp(-k t).
class ProtheroRobinson final : public OdeSystem {
 public:
  explicit ProtheroRobinson(double k) : k_(k) {}
  std::size_t continuous_size() const override { return 1; }
  void derivatives(double t, std::span<const double> y, std::span<const double>,
                   std::span<double> dydt) const override {
    dydt[0] = -k_ * (y[0] - std::cos(t)) - std::sin(t);
  }
  double exact(double t, double y0) const { return std::cos(t) + (y0 - 1) * std::exp(-k_ * t); }

 private:
  double k_;
};

}  // namespace wavebench::model::solver::testing
