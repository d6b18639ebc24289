#pragma once
// Dormand–Prince 5(4) (Hairer, Nørsett & Wanner's DOPRI5): FSAL, PI step-size control on the
// weighted RMS norm of the embedded error, and the method's own 4th-order continuous
// extension for dense output.

#include <vector>

#include "wavebench/model/solver/integrator.hpp"
#include "wavebench/model/solver/step_control.hpp"

namespace wavebench::model::solver {

class DormandPrince45 final : public Integrator {
 public:
  explicit DormandPrince45(const StepControl& control);

  std::string name() const override { return "DormandPrince45"; }
  int order() const override { return 5; }

  void initialize(const OdeSystem& system, double t0, std::span<const double> y0,
                  std::span<const double> d, double h0) override;
  double step(double t_max) override;
  void dense_output(double t, std::span<double> y) const override;

  double current_time() const override { return t_; }
  double previous_time() const override { return t_old_; }
  std::span<const double> current_state() const override { return y_; }
  void reset(double t, std::span<const double> y) override;
  const IntegratorCounters& counters() const override { return counters_; }

  // The step the controller proposes next.
  double proposed_step() const { return h_; }

 private:
  void evaluate(double t, const double* y, double* dydt);
  void prepare_dense_output() const;

  StepControl control_;
  const OdeSystem* system_ = nullptr;
  std::span<const double> d_;
  std::size_t n_ = 0;
  double t_ = 0, t_old_ = 0, h_ = 0, h_last_ = 0;
  double err_old_ = 1e-4;  // PI controller memory (Hairer's facold)
  bool last_rejected_ = false;
  std::vector<double> y_, y_old_, y_stage_, y_new_, error_scale_;
  std::vector<double> k1_, k2_, k3_, k4_, k5_, k6_, k7_;
  // Continuous extension coefficients, built on the first dense_output() call of a step.
  mutable std::vector<double> r1_, r2_, r3_, r4_, r5_;
  mutable bool dense_ready_ = false;
  IntegratorCounters counters_;
};

}  // namespace wavebench::model::solver
