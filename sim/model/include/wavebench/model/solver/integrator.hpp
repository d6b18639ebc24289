#pragma once
// Integrators are separate classes behind one small interface: initialise, take one step
// (the step hook), evaluate the dense output inside the last step. Event location and
// fixed-rate sampling are built on top of this (see simulate()), not inside each method.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "wavebench/model/solver/ode_system.hpp"

namespace wavebench::model::solver {

struct Tolerances {
  double rtol = 1e-6;
  double atol = 1e-9;  // multiplied by OdeSystem::error_scale()
};

struct IntegratorCounters {
  std::int64_t steps = 0;
  std::int64_t rejected_steps = 0;
  std::int64_t rhs_evaluations = 0;
  std::int64_t jacobian_evaluations = 0;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  Integrator() = default;
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  virtual std::string name() const = 0;
  virtual int order() const = 0;

  // Starts at (t0, y0) with discrete state d (the integrator keeps a reference to d; events
  // change it between steps). h0 = 0 lets an adaptive method choose its first step.
  virtual void initialize(const OdeSystem& system, double t0, std::span<const double> y0,
                          std::span<const double> d, double h0) = 0;

  // Advances one accepted step, never past t_max. Returns the new time.
  virtual double step(double t_max) = 0;

  // Dense output: the state at t in [previous_time(), current_time()].
  virtual void dense_output(double t, std::span<double> y) const = 0;

  virtual double current_time() const = 0;
  virtual double previous_time() const = 0;
  virtual std::span<const double> current_state() const = 0;

  // After an event changed the state or the discrete state at t: restart from there.
  virtual void reset(double t, std::span<const double> y) = 0;

  virtual const IntegratorCounters& counters() const = 0;
};

}  // namespace wavebench::model::solver
