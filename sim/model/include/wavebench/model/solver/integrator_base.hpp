#pragma once
// What every integrator shares (Drake's IntegratorBase idea): the system it integrates, the
// time of the last two accepted steps, the step size, the counters, the right-hand side call
// that counts itself, the input checks and the landing on t_max when only a rounding-sized
// remainder is left. A method implements only its hooks: DoInitialize (buffers), DoReset (the
// state at a restart), DoStep, DoLandInPlace and DoDenseOutput.

#include "wavebench/model/solver/integrator.hpp"
#include "wavebench/model/solver/step_control.hpp"

namespace wavebench::model::solver {

class IntegratorBase : public Integrator {
 public:
  void initialize(const OdeSystem& system, double t0, std::span<const double> y0,
                  std::span<const double> d, double h0) final;
  double step(double t_max) final;
  void dense_output(double t, std::span<double> y) const final { DoDenseOutput(t, y); }
  void reset(double t, std::span<const double> y) final;

  double current_time() const final { return t_; }
  double previous_time() const final { return t_old_; }
  const IntegratorCounters& counters() const final { return counters_; }

 protected:
  // Sizes the method's buffers for n_ states; h0 as initialize() got it.
  virtual void DoInitialize(double h0) = 0;
  // Restarts from y at t_ (== t_old_).
  virtual void DoReset(std::span<const double> y) = 0;
  // One accepted step from t_ towards t_max (t_max - t_ more than rounding); returns t_.
  virtual double DoStep(double t_max) = 0;
  // t_ has moved to t_max by a rounding-sized remainder: the state stays, the step is empty.
  virtual void DoLandInPlace() = 0;
  virtual void DoDenseOutput(double t, std::span<double> y) const = 0;

  void evaluate(double t, const double* y, double* dydt);

  const OdeSystem* system_ = nullptr;
  std::span<const double> d_;
  std::size_t n_ = 0;
  double t_ = 0, t_old_ = 0;
  double h_ = 0;  // the fixed step, or the step the controller proposes next
  IntegratorCounters counters_;
};

// The adaptive methods' step-size control: the settings and the controller's memory.
class AdaptiveIntegrator : public IntegratorBase {
 public:
  // The step the controller proposes next.
  double proposed_step() const { return h_; }

 protected:
  // Throws std::invalid_argument naming the field (validate(StepControl)).
  explicit AdaptiveIntegrator(const StepControl& control);

  StepControl control_;
  double h_last_ = 0;   // the last accepted step
  double err_old_ = 0;  // the controller's memory of the last accepted error
  bool last_rejected_ = false;
};

}  // namespace wavebench::model::solver
