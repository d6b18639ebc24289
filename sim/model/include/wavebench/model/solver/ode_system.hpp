#pragma once
// What an integrator advances. Drake's split: the system holds no changing data and computes
// derivatives in a const function; the state (continuous y and discrete d) lives apart, in the
// integrator's hands. Discrete state changes only at located events (witness sign changes).

#include <cstddef>
#include <span>

namespace wavebench::model::solver {

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;

  virtual std::size_t continuous_size() const = 0;
  virtual std::size_t discrete_size() const { return 0; }

  // dy/dt = f(t, y; d). Must not change anything: called at trial points the step may reject.
  virtual void derivatives(double t, std::span<const double> y, std::span<const double> d,
                           std::span<double> dydt) const = 0;

  // Characteristic size of each continuous state, so one rtol/atol pair means the same for an
  // angle deviation of arcseconds and a bristle deflection of nanometres: the error test uses
  // atol * scale[i] + rtol * |y[i]|.
  virtual void error_scale(std::span<double> scale) const {
    for (double& s : scale) s = 1.0;
  }

  // Event location: witness functions g_k(t, y; d); a sign change inside a step is located
  // on the dense output to the integrator's tolerance, then on_event() may update d (and y).
  virtual std::size_t witness_count() const { return 0; }
  virtual void witnesses(double /*t*/, std::span<const double> /*y*/, std::span<const double> /*d*/,
                         std::span<double> /*g*/) const {}
  virtual void on_event(std::size_t /*witness*/, double /*t*/, std::span<double> /*y*/,
                        std::span<double> /*d*/) const {}

  // Optional analytic Jacobian df/dy (row-major n x n) for implicit methods; false = the
  // integrator uses finite differences.
  virtual bool jacobian(double /*t*/, std::span<const double> /*y*/, std::span<const double> /*d*/,
                        std::span<double> /*dfdy*/) const {
    return false;
  }
};

}  // namespace wavebench::model::solver
