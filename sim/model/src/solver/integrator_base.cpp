#include "wavebench/model/solver/integrator_base.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace wavebench::model::solver {

void IntegratorBase::initialize(const OdeSystem& system, double t0, std::span<const double> y0,
                                std::span<const double> d, double h0) {
  system_ = &system;
  d_ = d;
  n_ = system.continuous_size();
  if (y0.size() != n_) {
    throw std::invalid_argument(name() + ": initial state has " + std::to_string(y0.size()) +
                                " values, the system " + std::to_string(n_));
  }
  DoInitialize(h0);
  counters_ = {};
  reset(t0, y0);
}

void IntegratorBase::reset(double t, std::span<const double> y) {
  t_ = t;
  t_old_ = t;
  DoReset(y);
}

double IntegratorBase::step(double t_max) {
  if (!(t_max > t_)) return t_;
  if (t_max - t_ <= 16 * std::numeric_limits<double>::epsilon() * std::fabs(t_max)) {
    // A rounding-sized remainder (e.g. an event just before t_max): no step can resolve it
    // and the state cannot change by more than rounding, so land on t_max in place.
    t_old_ = t_;
    t_ = t_max;
    DoLandInPlace();
    return t_;
  }
  return DoStep(t_max);
}

void IntegratorBase::evaluate(double t, const double* y, double* dydt) {
  system_->derivatives(t, {y, n_}, d_, {dydt, n_});
  ++counters_.rhs_evaluations;
}

AdaptiveIntegrator::AdaptiveIntegrator(const StepControl& control) : control_(control) {
  validate(control_);
}

}  // namespace wavebench::model::solver
